#include "performer/body_shape.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

namespace performer {

namespace {

void check_params(const BodyShapeParams& p) {
  auto positive = [](float v) { return v > 0.0f && std::isfinite(v); };
  if (!positive(p.thickness)) throw std::invalid_argument("body shape: thickness must be positive");
  if (!positive(p.taper_exponent)) throw std::invalid_argument("body shape: taper_exponent must be positive");
  if (!positive(p.torso_factor)) throw std::invalid_argument("body shape: torso_factor must be positive");
  if (!(p.limb_share > 0.0f && p.limb_share <= 1.0f))
    throw std::invalid_argument("body shape: limb_share must be in (0, 1]");
  if (!positive(p.min_radius)) throw std::invalid_argument("body shape: min_radius must be positive");
  if (!(p.blend >= 0.0f) || !std::isfinite(p.blend)) throw std::invalid_argument("body shape: blend must be >= 0");
  if (!(p.separation >= 0.0f) || !std::isfinite(p.separation))
    throw std::invalid_argument("body shape: separation must be >= 0");
  if (!(p.neck_radius >= 0.0f) || !std::isfinite(p.neck_radius))
    throw std::invalid_argument("body shape: neck_radius must be >= 0");
}

// Length of the path along the bones from joint x to joint y; infinite when they hang from
// different roots. rooted[j]: bone length from j's root down to j.
float path_length(const Skeleton& skeleton, std::span<const int> hops, std::span<const float> rooted, int x, int y) {
  const float through = rooted[static_cast<std::size_t>(x)] + rooted[static_cast<std::size_t>(y)];
  while (hops[static_cast<std::size_t>(x)] > hops[static_cast<std::size_t>(y)])
    x = skeleton.joints[static_cast<std::size_t>(x)].parent;
  while (hops[static_cast<std::size_t>(y)] > hops[static_cast<std::size_t>(x)])
    y = skeleton.joints[static_cast<std::size_t>(y)].parent;
  while (x != y) {
    x = skeleton.joints[static_cast<std::size_t>(x)].parent;
    y = skeleton.joints[static_cast<std::size_t>(y)].parent;
    if (x < 0 || y < 0) return std::numeric_limits<float>::infinity();
  }
  return through - 2.0f * rooted[static_cast<std::size_t>(x)];
}

// Capsules are related when the bones between them are shorter than the capsules are thick: they
// belong to one part of the body and should blend.
std::vector<std::uint8_t> related_capsules(const Skeleton& skeleton, std::span<const float> length,
                                           const std::vector<BoneCapsule>& capsules) {
  const std::size_t n = skeleton.joints.size();
  std::vector<int> hops(n, 0);
  std::vector<float> rooted(n, 0.0f);
  for (std::size_t j = 0; j < n; ++j) {
    const int parent = skeleton.joints[j].parent;
    if (parent < 0) continue;
    hops[j] = hops[static_cast<std::size_t>(parent)] + 1;
    rooted[j] = rooted[static_cast<std::size_t>(parent)] + length[j];
  }
  const std::size_t m = capsules.size();
  std::vector<std::uint8_t> related(m * m, 0);
  for (std::size_t a = 0; a < m; ++a)
    for (std::size_t b = a; b < m; ++b) {
      const BoneCapsule& ca = capsules[a];
      const BoneCapsule& cb = capsules[b];
      float path = std::numeric_limits<float>::infinity();
      for (const int x : {ca.parent, ca.joint})
        for (const int y : {cb.parent, cb.joint}) path = std::min(path, path_length(skeleton, hops, rooted, x, y));
      const float thickness = std::max(ca.radius_a, ca.radius_b) + std::max(cb.radius_a, cb.radius_b);
      related[a * m + b] = related[b * m + a] = path <= thickness ? 1 : 0;
    }
  return related;
}

// Polynomial smooth minimum: equal to min(a, b) once they differ by more than k, and below both in
// between by at most k / 4. It is C1, so the blended surface has no crease where two capsules meet.
float smooth_min(float a, float b, float k) {
  if (k <= 0.0f) return std::min(a, b);
  const float h = std::max(k - std::abs(a - b), 0.0f) / k;
  return std::min(a, b) - h * h * k * 0.25f;
}

}  // namespace

float skeleton_size(std::span<const glm::vec3> rest_positions) {
  if (rest_positions.empty()) return 0.0f;
  glm::vec3 lo = rest_positions[0], hi = rest_positions[0];
  for (const glm::vec3& p : rest_positions) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  const glm::vec3 extent = hi - lo;
  return std::max({extent.x, extent.y, extent.z});
}

BodyShape body_shape(const Skeleton& skeleton, std::span<const glm::vec3> rest_positions,
                     const BodyShapeParams& params) {
  check_params(params);
  const std::size_t n = skeleton.joints.size();
  if (rest_positions.size() != n)
    throw std::invalid_argument("body_shape: " + std::to_string(rest_positions.size()) + " positions for " +
                                std::to_string(n) + " joints");
  const float size = skeleton_size(rest_positions);
  const float min_length = 1e-6f * size;

  // Bone j runs from parent(j) to j. Sums below run children-to-parents, so parents must precede.
  std::vector<float> length(n, 0.0f);
  for (std::size_t j = 0; j < n; ++j) {
    const int parent = skeleton.joints[j].parent;
    if (parent < 0) continue;
    if (static_cast<std::size_t>(parent) >= j)
      throw std::invalid_argument("body_shape: joint " + std::to_string(j) + " has parent " + std::to_string(parent) +
                                  ", which does not precede it");
    length[j] = glm::distance(rest_positions[j], rest_positions[static_cast<std::size_t>(parent)]);
  }
  // below[j]: bone length in j's subtree; carried[j]: that plus bone j itself. limbs[j]: how many
  // large limbs hang below j (a large child with no large limbs of its own counts as one).
  std::vector<float> below(n, 0.0f), carried(n, 0.0f);
  float total = 0.0f;
  for (float l : length) total += l;
  BodyShape shape;
  shape.blend = params.blend * size;
  shape.separation = params.separation * size;
  if (!(total > 0.0f)) return shape;
  std::vector<int> limbs(n, 0);
  for (std::size_t j = n; j-- > 0;) {
    carried[j] = length[j] + below[j];
    const int parent = skeleton.joints[j].parent;
    if (parent < 0) continue;
    below[static_cast<std::size_t>(parent)] += carried[j];
    if (carried[j] >= params.limb_share * total) limbs[static_cast<std::size_t>(parent)] += std::max(1, limbs[j]);
  }

  // Bones starting at the excluded joint or anywhere below it belong to the head.
  const int excluded = params.exclude_from.empty() ? -1 : find_joint(skeleton, params.exclude_from);
  std::vector<bool> in_excluded(n, false);
  for (std::size_t j = 0; j < n; ++j) {
    const int parent = skeleton.joints[j].parent;
    in_excluded[j] = static_cast<int>(j) == excluded || (parent >= 0 && in_excluded[static_cast<std::size_t>(parent)]);
  }

  // The neck: bones from the attach joint up towards the torso, stopping at the first torso bone.
  std::vector<bool> neck(n, false);
  for (int j = excluded;
       j >= 0 && skeleton.joints[static_cast<std::size_t>(j)].parent >= 0 && limbs[static_cast<std::size_t>(j)] < 2;
       j = skeleton.joints[static_cast<std::size_t>(j)].parent)
    neck[static_cast<std::size_t>(j)] = true;

  const float scale = params.thickness * size;
  const float floor_radius = params.min_radius * size;
  auto radius = [&](float share_length, bool torso) {
    const float r =
        scale * std::pow(share_length / total, params.taper_exponent) * (torso ? params.torso_factor : 1.0f);
    return std::max(r, floor_radius);
  };

  std::vector<BoneCapsule>& capsules = shape.capsules;
  for (std::size_t j = 0; j < n; ++j) {
    const int parent = skeleton.joints[j].parent;
    if (parent < 0 || !(length[j] > min_length) || in_excluded[static_cast<std::size_t>(parent)]) continue;
    const bool torso = limbs[j] >= 2;
    BoneCapsule c;
    c.parent = parent;
    c.joint = static_cast<int>(j);
    c.a = rest_positions[static_cast<std::size_t>(parent)];
    c.b = rest_positions[j];
    c.radius_a = radius(carried[j], torso);
    // Into the attach joint the bone stays full width: the separate head sits on a neck, not a point.
    c.radius_b = static_cast<int>(j) == excluded ? c.radius_a : radius(below[j], torso);
    if (neck[j]) {
      c.radius_a = std::max(c.radius_a, params.neck_radius * size);
      c.radius_b = std::max(c.radius_b, params.neck_radius * size);
    }
    capsules.push_back(c);
  }
  shape.related = related_capsules(skeleton, length, capsules);
  return shape;
}

BonePoint nearest_on_bone(const BoneCapsule& capsule, const glm::vec3& p) {
  const glm::vec3 ab = capsule.b - capsule.a;
  const float length2 = glm::dot(ab, ab);
  const float t = length2 > 0.0f ? std::clamp(glm::dot(p - capsule.a, ab) / length2, 0.0f, 1.0f) : 0.0f;
  return {t, glm::distance(p, capsule.a + t * ab)};
}

float capsule_field(const BoneCapsule& capsule, const glm::vec3& p) {
  const BonePoint nearest = nearest_on_bone(capsule, p);
  return nearest.distance - (capsule.radius_a + (capsule.radius_b - capsule.radius_a) * nearest.t);
}

float body_field(const BodyShape& shape, const glm::vec3& p) {
  const std::size_t n = shape.capsules.size();
  if (n == 0) return std::numeric_limits<float>::infinity();
  // Per-thread scratch: the field is evaluated hundreds of thousands of times per mesh.
  thread_local std::vector<float> d;
  d.resize(n);
  d[0] = capsule_field(shape.capsules[0], p);
  float nearest = d[0], blended = d[0];
  for (std::size_t i = 1; i < n; ++i) {
    d[i] = capsule_field(shape.capsules[i], p);
    nearest = std::min(nearest, d[i]);
    blended = smooth_min(blended, d[i], shape.blend);
  }
  if (!(shape.separation > 0.0f)) return blended;
  // The cut: for unrelated capsules a, b, g + 2m - d_a - d_b (m the nearest field) is positive only
  // where both are within g of the nearest, i.e. within g of the surface halfway between them. It is
  // continuous in p, and only capsules within g of the nearest can make it positive. It may not eat
  // into a capsule related to both (the collar between upper arm and chest): min with that field.
  const float g = shape.separation;
  float cut = -std::numeric_limits<float>::infinity();
  for (std::size_t a = 0; a < n; ++a) {
    if (d[a] - nearest >= g) continue;
    for (std::size_t b = a + 1; b < n; ++b) {
      if (d[b] - nearest >= g || shape.related[a * n + b]) continue;
      float pair = g + 2.0f * nearest - d[a] - d[b];
      for (std::size_t c = 0; c < n; ++c)
        if (shape.related[a * n + c] && shape.related[b * n + c]) pair = std::min(pair, d[c]);
      cut = std::max(cut, pair);
    }
  }
  return std::max(blended, cut);
}

}  // namespace performer
