#include "performer/scalar_grid.h"

#include <cmath>
#include <stdexcept>

#include "base/thread_pool.h"

namespace performer {

ScalarGrid sample_grid(const glm::vec3& lo, const glm::vec3& hi, float cell,
                       const std::function<float(const glm::vec3&)>& f, unsigned threads) {
  if (!(cell > 0.0f) || !std::isfinite(cell)) throw std::invalid_argument("sample_grid: cell must be positive");
  const glm::vec3 extent = hi - lo;
  if (!(extent.x >= 0.0f && extent.y >= 0.0f && extent.z >= 0.0f) || !std::isfinite(extent.x + extent.y + extent.z))
    throw std::invalid_argument("sample_grid: empty or non-finite box");
  ScalarGrid grid;
  grid.cell = cell;
  // Enough cells to cover the extent; the slack is shared equally on both sides.
  const double cx = std::ceil(extent.x / cell), cy = std::ceil(extent.y / cell), cz = std::ceil(extent.z / cell);
  if ((cx + 1.0) * (cy + 1.0) * (cz + 1.0) > 2147483648.0)
    throw std::invalid_argument("sample_grid: more than 2^31 samples; use a larger cell");
  grid.nx = static_cast<int>(cx) + 1;
  grid.ny = static_cast<int>(cy) + 1;
  grid.nz = static_cast<int>(cz) + 1;
  const glm::vec3 covered = cell * glm::vec3(static_cast<float>(cx), static_cast<float>(cy), static_cast<float>(cz));
  grid.origin = lo - 0.5f * (covered - extent);
  grid.values.resize(static_cast<std::size_t>(grid.nx) * static_cast<std::size_t>(grid.ny) *
                     static_cast<std::size_t>(grid.nz));
  // One z slab per work item: slabs are independent and each writes its own contiguous range.
  base::parallel_for(static_cast<std::size_t>(grid.nz), 1, threads, [&](std::size_t begin, std::size_t end) {
    for (auto k = static_cast<int>(begin); k < static_cast<int>(end); ++k)
      for (int j = 0; j < grid.ny; ++j)
        for (int i = 0; i < grid.nx; ++i) grid.values[grid.index(i, j, k)] = f(grid.position(i, j, k));
  });
  return grid;
}

}  // namespace performer
