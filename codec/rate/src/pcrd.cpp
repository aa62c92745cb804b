#include "codec/rate/pcrd.h"

namespace codec::rate {

Selection select_for_budget(std::span<const std::vector<HullPoint>> hulls, std::size_t budget) {
  return RateAllocator(hulls).for_budget(budget);
}

Selection select_for_distortion(std::span<const std::vector<HullPoint>> hulls, double total_weighted_energy,
                                double max_distortion) {
  return RateAllocator(hulls).for_distortion(total_weighted_energy, max_distortion);
}

std::vector<std::vector<int>> layer_passes(std::span<const std::vector<HullPoint>> hulls,
                                           std::span<const std::size_t> budgets) {
  return RateAllocator(hulls).layers(budgets);
}

}  // namespace codec::rate
