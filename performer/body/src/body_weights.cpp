#include "performer/body_weights.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "base/thread_pool.h"

namespace performer {

namespace {

constexpr std::size_t kWeightVerticesPerChunk = 1024;

// Each capsule's neighbours along the skeleton: the bones ending at its first joint (its parent
// bone; one, or none at the root) and those starting at its second joint (its child bones).
std::vector<std::vector<std::size_t>> skeleton_neighbours(const BodyShape& shape) {
  const std::size_t n = shape.capsules.size();
  std::vector<std::vector<std::size_t>> out(n);
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < n; ++j) {
      if (i == j) continue;
      const BoneCapsule &a = shape.capsules[i], &b = shape.capsules[j];
      if (b.joint == a.parent || b.parent == a.joint) out[i].push_back(j);
    }
  return out;
}

// Vertex neighbours over the triangles, as compressed rows: vertex v's are
// neighbours[offsets[v] .. offsets[v + 1]).
struct Adjacency {
  std::vector<std::uint32_t> offsets;
  std::vector<std::uint32_t> neighbours;
};

Adjacency vertex_adjacency(std::size_t vertices, std::span<const std::uint32_t> triangles) {
  std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;
  pairs.reserve(triangles.size() * 2);
  for (std::size_t t = 0; t + 2 < triangles.size(); t += 3)
    for (int e = 0; e < 3; ++e) {
      const std::uint32_t a = triangles[t + e], b = triangles[t + (e + 1) % 3];
      if (a == b || a >= vertices || b >= vertices) continue;
      pairs.emplace_back(a, b);
      pairs.emplace_back(b, a);
    }
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  Adjacency adj;
  adj.offsets.assign(vertices + 1, 0);
  for (const auto& [a, b] : pairs) ++adj.offsets[a + 1];
  for (std::size_t v = 0; v < vertices; ++v) adj.offsets[v + 1] += adj.offsets[v];
  adj.neighbours.reserve(pairs.size());
  for (const auto& [a, b] : pairs) adj.neighbours.push_back(b);
  return adj;
}

// The seeds: 1 / d^falloff over the vertex's own bone and its neighbours along the skeleton,
// normalised, as a dense row over the driving joints (`column` maps a joint to its column).
void seed_range(const BodyShape& shape, const std::vector<std::vector<std::size_t>>& neighbours,
                const std::vector<int>& column, std::size_t columns, std::span<const glm::vec3> positions,
                float inverse_scale, const BodyWeightParams& p, std::vector<float>& dense, std::size_t begin,
                std::size_t end) {
  for (std::size_t v = begin; v < end; ++v) {
    const glm::vec3 x = positions[v] * inverse_scale;
    std::size_t own = 0;
    float lowest = std::numeric_limits<float>::infinity();
    for (std::size_t c = 0; c < shape.capsules.size(); ++c) {
      const float f = capsule_field(shape.capsules[c], x);
      if (f < lowest) lowest = f, own = c;
    }
    float* row = dense.data() + v * columns;
    const float nearest = std::max(nearest_on_bone(shape.capsules[own], x).distance, p.min_distance);
    auto consider = [&](std::size_t c) {
      const float d = std::max(nearest_on_bone(shape.capsules[c], x).distance, p.min_distance);
      // (d_own / d)^n: k / d^n scaled by the owner's, in (0, 1] for the nearer bones.
      const float w = std::pow(nearest / d, p.falloff);
      float& slot = row[static_cast<std::size_t>(column[static_cast<std::size_t>(shape.capsules[c].parent)])];
      slot = std::max(slot, w);
    };
    consider(own);
    for (const std::size_t c : neighbours[own]) consider(c);
    float sum = 0.0f;
    for (std::size_t j = 0; j < columns; ++j) sum += row[j];
    for (std::size_t j = 0; j < columns; ++j) row[j] /= sum;
  }
}

}  // namespace

void body_ssd_weights(const BodyShape& shape, std::span<const glm::vec3> rest_positions,
                      std::span<const std::uint32_t> triangles, float scale, const BodyWeightParams& params,
                      std::span<std::uint16_t> out_joints, std::span<float> out_weights, unsigned threads) {
  if (!(params.falloff >= 0.0f) || !std::isfinite(params.falloff))
    throw std::invalid_argument("body_ssd_weights: falloff must be non-negative");
  if (!(params.min_distance > 0.0f)) throw std::invalid_argument("body_ssd_weights: min_distance must be positive");
  if (params.max_influences < 1 || params.max_influences > kMaxInfluences)
    throw std::invalid_argument("body_ssd_weights: max_influences must be 1 to " + std::to_string(kMaxInfluences));
  if (!(scale > 0.0f) || !std::isfinite(scale)) throw std::invalid_argument("body_ssd_weights: scale must be positive");
  if (shape.capsules.empty()) throw std::invalid_argument("body_ssd_weights: the shape has no capsules");
  if (params.smoothing_steps < 0) throw std::invalid_argument("body_ssd_weights: smoothing_steps must not be negative");
  for (const BoneCapsule& c : shape.capsules)
    if (c.parent < 0 || c.parent > std::numeric_limits<std::uint16_t>::max())
      throw std::invalid_argument("body_ssd_weights: a capsule's joint index does not fit 16 bits");
  const std::size_t total_slots = rest_positions.size() * static_cast<std::size_t>(params.max_influences);
  if (out_joints.size() != total_slots || out_weights.size() != total_slots)
    throw std::invalid_argument("body_ssd_weights: outputs hold " + std::to_string(out_joints.size()) + " and " +
                                std::to_string(out_weights.size()) + " slots, expected " + std::to_string(total_slots));
  const std::size_t n = rest_positions.size();
  // The joints that move some capsule, one dense column each.
  std::vector<int> column(static_cast<std::size_t>(std::numeric_limits<std::uint16_t>::max()) + 1, -1);
  std::vector<std::uint16_t> joint_of;
  for (const BoneCapsule& c : shape.capsules)
    if (column[static_cast<std::size_t>(c.parent)] < 0) {
      column[static_cast<std::size_t>(c.parent)] = static_cast<int>(joint_of.size());
      joint_of.push_back(static_cast<std::uint16_t>(c.parent));
    }
  const std::size_t columns = joint_of.size();
  std::vector<float> dense(n * columns, 0.0f), next(n * columns);
  const auto neighbours = skeleton_neighbours(shape);
  base::parallel_for(n, kWeightVerticesPerChunk, threads, [&](std::size_t begin, std::size_t end) {
    seed_range(shape, neighbours, column, columns, rest_positions, 1.0f / scale, params, dense, begin, end);
  });

  // Diffusion over the surface: the seeds jump from bone to bone at every seam (between skeleton
  // neighbours, and where the skin of bones that are not neighbours meets: the chest and the neck
  // above a short neck base, the wrist and the thumb). Jacobi steps of w <- (w + mean of the
  // neighbours' w) / 2 turn each jump into a blend along the surface, and never carry weight across
  // the gaps body_shape keeps between unrelated limbs.
  const Adjacency adj = vertex_adjacency(n, triangles);
  for (int step = 0; step < params.smoothing_steps; ++step) {
    base::parallel_for(n, kWeightVerticesPerChunk, threads, [&](std::size_t begin, std::size_t end) {
      for (std::size_t v = begin; v < end; ++v) {
        const std::uint32_t first = adj.offsets[v], last = adj.offsets[v + 1];
        float* out = next.data() + v * columns;
        const float* own = dense.data() + v * columns;
        if (first == last) {
          std::copy(own, own + columns, out);
          continue;
        }
        const float share = 0.5f / static_cast<float>(last - first);
        for (std::size_t j = 0; j < columns; ++j) out[j] = 0.5f * own[j];
        for (std::uint32_t k = first; k < last; ++k) {
          const float* other = dense.data() + static_cast<std::size_t>(adj.neighbours[k]) * columns;
          for (std::size_t j = 0; j < columns; ++j) out[j] += share * other[j];
        }
      }
    });
    dense.swap(next);
  }

  // The strongest max_influences joints, normalised; ties to the lower joint index.
  const auto slots = static_cast<std::size_t>(params.max_influences);
  base::parallel_for(n, kWeightVerticesPerChunk, threads, [&](std::size_t begin, std::size_t end) {
    std::vector<std::size_t> order(columns);
    for (std::size_t v = begin; v < end; ++v) {
      const float* row = dense.data() + v * columns;
      for (std::size_t j = 0; j < columns; ++j) order[j] = j;
      const std::size_t kept = std::min(slots, columns);
      std::partial_sort(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(kept), order.end(),
                        [&](std::size_t a, std::size_t b) {
                          return row[a] > row[b] || (row[a] == row[b] && joint_of[a] < joint_of[b]);
                        });
      float sum = 0.0f;
      for (std::size_t i = 0; i < kept; ++i) sum += row[order[i]];
      for (std::size_t i = 0; i < slots; ++i) {
        const bool used = i < kept && row[order[i]] > 0.0f;
        out_joints[v * slots + i] = used ? joint_of[order[i]] : 0;
        out_weights[v * slots + i] = used ? row[order[i]] / sum : 0.0f;
      }
    }
  });
}

}  // namespace performer
