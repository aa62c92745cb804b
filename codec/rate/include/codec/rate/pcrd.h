#pragma once
#include <cstddef>
#include <span>
#include <vector>

#include "codec/rate/hull.h"
#include "codec/rate/rate_allocator.h"
#include "codec/rate/selection.h"

namespace codec::rate {

// One-shot PCRD-opt queries: each builds a RateAllocator over `hulls` and asks it once. An encoder
// asking several budgets of the same hulls should keep one RateAllocator instead, since building
// it (sorting every hull step) is the expensive part. See RateAllocator for the exact guarantees.

// The selection that fits `budget` code-block data bytes: the limit of bisection on the slope
// threshold, with ties split and the left-over room filled greedily by whole hull steps.
Selection select_for_budget(std::span<const std::vector<HullPoint>> hulls, std::size_t budget);

// The selection with the fewest bytes (among slope-ordered prefixes, so among threshold selections
// too) whose remaining distortion total_weighted_energy - distortion is <= max_distortion.
Selection select_for_distortion(std::span<const std::vector<HullPoint>> hulls, double total_weighted_energy,
                                double max_distortion);

// Cumulative passes per block for each quality layer (result[layer][block]); budgets must not
// decrease, and pass counts never decrease from one layer to the next.
std::vector<std::vector<int>> layer_passes(std::span<const std::vector<HullPoint>> hulls,
                                           std::span<const std::size_t> budgets);

}  // namespace codec::rate
