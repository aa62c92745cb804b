#include "performer/mesh_smooth.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "base/thread_pool.h"

namespace performer {

namespace {

constexpr std::size_t kSmoothVerticesPerChunk = 4096;

// Each vertex's distinct edge neighbours, compressed: neighbours of v are
// list[offset[v] .. offset[v + 1]).
struct Neighbours {
  std::vector<std::uint32_t> offset, list;
};

Neighbours edge_neighbours(std::size_t vertex_count, std::span<const std::uint32_t> indices) {
  Neighbours n;
  std::vector<std::uint32_t> count(vertex_count + 1, 0);
  for (std::size_t t = 0; t < indices.size(); t += 3)
    for (int e = 0; e < 3; ++e) count[indices[t + static_cast<std::size_t>(e)]] += 2;  // both other corners
  std::vector<std::uint32_t> start(vertex_count + 1, 0);
  for (std::size_t v = 0; v < vertex_count; ++v) start[v + 1] = start[v] + count[v];
  std::vector<std::uint32_t> raw(start[vertex_count]);
  std::vector<std::uint32_t> fill(start.begin(), start.end() - 1);
  for (std::size_t t = 0; t < indices.size(); t += 3)
    for (int e = 0; e < 3; ++e) {
      const std::uint32_t v = indices[t + static_cast<std::size_t>(e)];
      raw[fill[v]++] = indices[t + static_cast<std::size_t>((e + 1) % 3)];
      raw[fill[v]++] = indices[t + static_cast<std::size_t>((e + 2) % 3)];
    }
  // Every interior edge was seen from both of its triangles: keep each neighbour once.
  n.offset.assign(vertex_count + 1, 0);
  n.list.reserve(raw.size() / 2);
  for (std::size_t v = 0; v < vertex_count; ++v) {
    const auto first = raw.begin() + start[v], last = raw.begin() + start[v + 1];
    std::sort(first, last);
    const auto end = std::unique(first, last);
    n.list.insert(n.list.end(), first, end);
    n.offset[v + 1] = static_cast<std::uint32_t>(n.list.size());
  }
  return n;
}

void step(const Neighbours& n, std::span<const glm::vec3> in, std::span<glm::vec3> out, float factor,
          unsigned threads) {
  base::parallel_for(in.size(), kSmoothVerticesPerChunk, threads, [&](std::size_t begin, std::size_t end) {
    for (std::size_t v = begin; v < end; ++v) {
      const std::uint32_t first = n.offset[v], last = n.offset[v + 1];
      if (first == last) {
        out[v] = in[v];
        continue;
      }
      glm::vec3 sum(0.0f);
      for (std::uint32_t i = first; i < last; ++i) sum += in[n.list[i]];
      const glm::vec3 average = sum / static_cast<float>(last - first);
      out[v] = in[v] + factor * (average - in[v]);
    }
  });
}

}  // namespace

void taubin_smooth(std::span<glm::vec3> positions, std::span<const std::uint32_t> indices, const TaubinParams& params,
                   unsigned threads) {
  if (params.iterations < 0) throw std::invalid_argument("taubin_smooth: iterations must be >= 0");
  if (!(params.lambda > 0.0f && params.lambda < 1.0f))
    throw std::invalid_argument("taubin_smooth: lambda must be in (0, 1)");
  if (!(params.mu < -params.lambda) || !std::isfinite(params.mu))
    throw std::invalid_argument("taubin_smooth: mu must be below -lambda");
  if (indices.size() % 3 != 0) throw std::invalid_argument("taubin_smooth: index count is not a multiple of 3");
  for (const std::uint32_t i : indices)
    if (i >= positions.size())
      throw std::invalid_argument("taubin_smooth: index " + std::to_string(i) + " out of range for " +
                                  std::to_string(positions.size()) + " vertices");
  if (params.iterations == 0 || positions.empty()) return;
  const Neighbours n = edge_neighbours(positions.size(), indices);
  std::vector<glm::vec3> scratch(positions.size());
  for (int it = 0; it < params.iterations; ++it) {
    step(n, positions, scratch, params.lambda, threads);
    step(n, scratch, positions, params.mu, threads);
  }
}

}  // namespace performer
