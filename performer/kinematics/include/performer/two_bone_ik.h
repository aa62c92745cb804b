// Two-bone inverse kinematics (thesis 3.5.2, equations 3.14-3.16): the analytic solution for a
// hip-knee-ankle or shoulder-elbow-wrist chain. Computed in double: the solution feeds back into
// forward kinematics, and the round trip should hold to well under a micrometre-scale tolerance.
#pragma once

#include <glm/ext/quaternion_double.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace performer {

// Equation 3.14: end of a planar two-link chain rooted at the origin, link lengths l1 and l2,
// theta1 the first link's angle from the x axis, theta2 the second's relative to the first (radians).
glm::dvec2 planar_two_bone_fk(double l1, double l2, double theta1, double theta2);

struct PlanarTwoBoneSolution {
  double theta1 = 0.0;  // radians, as in planar_two_bone_fk
  double theta2 = 0.0;
  // False when the target lies beyond l1 + l2 or inside |l1 - l2|; the angles then give the pose
  // whose end comes closest (the chain stretched toward the target, or folded back on itself).
  bool reachable = true;
};

// Equations 3.16 then 3.15: theta2 = +-acos((x^2 + y^2 - l1^2 - l2^2) / (2 l1 l2)), and theta1 from
// the tangent form of 3.15 evaluated with atan2 (which resolves the quadrant the printed ratio
// leaves open). bend_positive picks the sign of theta2, i.e. which way the middle joint bends.
// Throws std::invalid_argument unless both lengths are positive and finite.
PlanarTwoBoneSolution solve_planar_two_bone(double l1, double l2, glm::dvec2 target, bool bend_positive = true);

// A chain in world space: root (hip, shoulder), mid (knee, elbow) and end (ankle, wrist) joints.
// The bone lengths are |mid - root| and |end - mid|.
struct TwoBoneChain {
  glm::dvec3 root{0.0};
  glm::dvec3 mid{0.0};
  glm::dvec3 end{0.0};
};

struct TwoBoneIkResult {
  glm::dvec3 mid{0.0};  // solved joint positions (root does not move)
  glm::dvec3 end{0.0};
  // World-space rotations that carry the chain onto the solution, ready to premultiply the joints'
  // world rotations: root_rotation turns the whole chain about `root` so the upper bone points at
  // the solved mid; mid_rotation then turns the lower bone about the solved mid. Both are the
  // smallest such rotations, so bone twist is left as it was.
  glm::dquat root_rotation{1.0, 0.0, 0.0, 0.0};
  glm::dquat mid_rotation{1.0, 0.0, 0.0, 0.0};
  // The planar solution in the bend plane, with x from root toward the target and y toward the pole:
  // the mid joint bends toward the pole, so theta1 >= 0 and theta2 <= 0.
  double theta1 = 0.0;
  double theta2 = 0.0;
  bool reachable = true;  // as in PlanarTwoBoneSolution; the result is then the closest reach
};

// Places the planar solution in 3-D: the bend plane contains root, target and `pole` (a point the
// middle joint should bend toward, like a knee or elbow target). When the pole is on the root-target
// line the current mid joint picks the plane instead, and failing that any plane does.
// Throws std::invalid_argument for a chain with a zero-length bone.
TwoBoneIkResult solve_two_bone_ik(const TwoBoneChain& chain, const glm::dvec3& target, const glm::dvec3& pole);

}  // namespace performer
