#include "performer/ssd_weights.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include <glm/geometric.hpp>

#include "base/thread_pool.h"

namespace performer {

namespace {

constexpr std::size_t kWeightVerticesPerChunk = 2048;

void weights_range(std::span<const glm::vec3> vertices, std::span<const glm::vec3> joints, const SsdWeightParams& p,
                   std::span<std::uint16_t> out_joints, std::span<float> out_weights, std::size_t begin,
                   std::size_t end) {
  const auto slots = static_cast<std::size_t>(p.max_influences);
  const std::size_t kept_max = std::min(slots, joints.size());
  for (std::size_t v = begin; v < end; ++v) {
    // The nearest joints are the strongest (w falls with distance for n > 0; for n = 0 all tie and
    // the lowest indices win), so selecting by distance is selecting by weight. Insertion into a
    // short sorted list: joints number in the tens, slots in the units.
    std::array<float, kMaxInfluences> dist{};
    std::array<std::uint16_t, kMaxInfluences> index{};
    std::size_t kept = 0;
    for (std::size_t b = 0; b < joints.size(); ++b) {
      const float d = std::max(glm::length(vertices[v] - joints[b]), p.min_distance);
      if (kept == kept_max && !(d < dist[kept - 1])) continue;
      std::size_t at = kept < kept_max ? kept++ : kept - 1;
      while (at > 0 && d < dist[at - 1]) {
        dist[at] = dist[at - 1];
        index[at] = index[at - 1];
        --at;
      }
      dist[at] = d;
      index[at] = static_cast<std::uint16_t>(b);
    }
    // w_b = k / d_b^n, normalised. Dividing through by k / d_0^n (d_0 the nearest) gives
    // (d_0 / d_b)^n, which lies in (0, 1]: no overflow for large n or tiny distances, and the sum
    // is at least 1.
    std::array<float, kMaxInfluences> w{};
    float sum = 0.0f;
    for (std::size_t i = 0; i < kept; ++i) {
      w[i] = std::pow(dist[0] / dist[i], p.n);
      sum += w[i];
    }
    const std::size_t base = v * slots;
    for (std::size_t i = 0; i < slots; ++i) {
      out_joints[base + i] = i < kept ? index[i] : 0;
      out_weights[base + i] = i < kept ? w[i] / sum : 0.0f;
    }
  }
}

}  // namespace

void ssd_weights(std::span<const glm::vec3> rest_positions, std::span<const glm::vec3> joint_positions,
                 const SsdWeightParams& params, std::span<std::uint16_t> out_joints, std::span<float> out_weights,
                 unsigned threads) {
  if (!(params.k > 0.0f) || !std::isfinite(params.k)) throw std::invalid_argument("ssd_weights: k must be positive");
  if (!(params.n >= 0.0f) || !std::isfinite(params.n))
    throw std::invalid_argument("ssd_weights: n must be non-negative");
  if (!(params.min_distance > 0.0f)) throw std::invalid_argument("ssd_weights: min_distance must be positive");
  if (params.max_influences < 1 || params.max_influences > kMaxInfluences)
    throw std::invalid_argument("ssd_weights: max_influences must be 1 to " + std::to_string(kMaxInfluences));
  if (joint_positions.empty()) throw std::invalid_argument("ssd_weights: no joints");
  if (joint_positions.size() > std::numeric_limits<std::uint16_t>::max() + std::size_t{1})
    throw std::invalid_argument("ssd_weights: more joints than 16-bit indices can name");
  const std::size_t slots = rest_positions.size() * static_cast<std::size_t>(params.max_influences);
  if (out_joints.size() != slots || out_weights.size() != slots)
    throw std::invalid_argument("ssd_weights: outputs hold " + std::to_string(out_joints.size()) + " and " +
                                std::to_string(out_weights.size()) + " slots, expected " + std::to_string(slots));
  base::parallel_for(rest_positions.size(), kWeightVerticesPerChunk, threads, [&](std::size_t begin, std::size_t end) {
    weights_range(rest_positions, joint_positions, params, out_joints, out_weights, begin, end);
  });
}

}  // namespace performer
