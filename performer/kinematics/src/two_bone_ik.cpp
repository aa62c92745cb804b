#include "performer/two_bone_ik.h"

#include <algorithm>
#include <numbers>
#include <cmath>
#include <stdexcept>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>

namespace performer {

namespace {

// Targets exactly at full extension or full fold should count as reachable even when rounding puts
// them a few ulps outside.
constexpr double kReachSlack = 1e-12;

// The smallest rotation taking direction `from` to direction `to`.
glm::dquat rotation_between(glm::dvec3 from, glm::dvec3 to) {
  from = glm::normalize(from);
  to = glm::normalize(to);
  const double d = glm::dot(from, to);
  if (d < -1.0 + 1e-12) {
    // Opposite: any axis perpendicular to `from` works; take the one least parallel to it.
    const glm::dvec3 other = std::abs(from.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
    return glm::angleAxis(std::numbers::pi, glm::normalize(glm::cross(from, other)));
  }
  // Half-way quaternion: (1 + cos a, sin a * axis) normalised is (cos a/2, sin a/2 * axis),
  // without evaluating an angle.
  const glm::dvec3 axis = glm::cross(from, to);
  return glm::normalize(glm::dquat(1.0 + d, axis.x, axis.y, axis.z));
}

// A unit vector perpendicular to unit `x`.
glm::dvec3 any_perpendicular(const glm::dvec3& x) {
  const glm::dvec3 other = std::abs(x.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
  return glm::normalize(other - glm::dot(other, x) * x);
}

}  // namespace

glm::dvec2 planar_two_bone_fk(double l1, double l2, double theta1, double theta2) {
  return {l1 * std::cos(theta1) + l2 * std::cos(theta1 + theta2),
          l1 * std::sin(theta1) + l2 * std::sin(theta1 + theta2)};
}

PlanarTwoBoneSolution solve_planar_two_bone(double l1, double l2, glm::dvec2 target, bool bend_positive) {
  if (!(l1 > 0.0) || !(l2 > 0.0) || !std::isfinite(l1) || !std::isfinite(l2))
    throw std::invalid_argument("two-bone IK needs two positive bone lengths");
  const double x = target.x;
  const double y = target.y;
  const double distance = std::hypot(x, y);
  PlanarTwoBoneSolution s;
  s.reachable = distance <= (l1 + l2) * (1.0 + kReachSlack) && distance >= std::abs(l1 - l2) * (1.0 - kReachSlack);

  // (3.16). Clamping is what turns an unreachable target into the closest reach: cos = 1 stretches
  // the chain straight, cos = -1 folds it.
  const double cos2 = std::clamp((x * x + y * y - l1 * l1 - l2 * l2) / (2.0 * l1 * l2), -1.0, 1.0);
  const double sign = bend_positive ? 1.0 : -1.0;
  s.theta2 = sign * std::acos(cos2);
  // sqrt rather than sin(acos(.)) keeps full precision near the fully stretched pose.
  const double sin2 = sign * std::sqrt(std::max(0.0, 1.0 - cos2 * cos2));

  // (3.15): with A = l1 + l2 cos(theta2) and B = l2 sin(theta2), (3.14) reads
  // (x, y) = [A -B; B A] (cos theta1, sin theta1), so (cos, sin) theta1 ~ (A x + B y, A y - B x).
  const double a = l1 + l2 * cos2;
  const double b = l2 * sin2;
  s.theta1 = std::atan2(a * y - b * x, a * x + b * y);
  return s;
}

TwoBoneIkResult solve_two_bone_ik(const TwoBoneChain& chain, const glm::dvec3& target, const glm::dvec3& pole) {
  const glm::dvec3 upper = chain.mid - chain.root;
  const glm::dvec3 lower = chain.end - chain.mid;
  const double l1 = glm::length(upper);
  const double l2 = glm::length(lower);
  if (!(l1 > 0.0) || !(l2 > 0.0)) throw std::invalid_argument("two-bone IK: the chain has a zero-length bone");

  // Bend-plane frame: x toward the target, y toward the pole (both perpendicular).
  const glm::dvec3 to_target = target - chain.root;
  const double distance = glm::length(to_target);
  const double tiny = 1e-12 * (l1 + l2);
  glm::dvec3 x_axis;
  if (distance > tiny) {
    x_axis = to_target / distance;
  } else if (glm::length(chain.end - chain.root) > tiny) {
    x_axis = glm::normalize(chain.end - chain.root);  // target on the root: keep the current heading
  } else {
    x_axis = glm::normalize(upper);
  }
  glm::dvec3 y_axis{0.0};
  for (const glm::dvec3& hint : {pole - chain.root, upper}) {
    const glm::dvec3 across = hint - glm::dot(hint, x_axis) * x_axis;
    if (glm::length(across) > tiny) {
      y_axis = glm::normalize(across);
      break;
    }
  }
  if (y_axis == glm::dvec3(0.0)) y_axis = any_perpendicular(x_axis);

  // Bending negatively in (x, y) puts the mid joint on the +y side, toward the pole.
  const PlanarTwoBoneSolution planar = solve_planar_two_bone(l1, l2, {distance, 0.0}, /*bend_positive=*/false);
  const double a1 = planar.theta1;
  const double a12 = planar.theta1 + planar.theta2;

  TwoBoneIkResult r;
  r.theta1 = planar.theta1;
  r.theta2 = planar.theta2;
  r.reachable = planar.reachable;
  r.mid = chain.root + l1 * (std::cos(a1) * x_axis + std::sin(a1) * y_axis);
  r.end = r.mid + l2 * (std::cos(a12) * x_axis + std::sin(a12) * y_axis);
  r.root_rotation = rotation_between(upper, r.mid - chain.root);
  r.mid_rotation = rotation_between(r.root_rotation * lower, r.end - r.mid);
  return r;
}

}  // namespace performer
