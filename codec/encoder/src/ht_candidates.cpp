#include "ht_candidates.h"

namespace codec {

int HtCandidates::highest_coded() const {
  for (int p = static_cast<int>(by_plane.size()) - 1; p >= 0; --p)
    if (by_plane[static_cast<std::size_t>(p)]) return p;
  return -1;
}

int HtCandidates::lowest_coded() const {
  for (std::size_t p = 0; p < by_plane.size(); ++p)
    if (by_plane[p]) return static_cast<int>(p);
  return -1;
}

void add_candidates(HtCandidates& candidates, const ht::HtBlock& block, std::span<const int> planes,
                    ht::HtPasses passes) {
  candidates.by_plane.resize(static_cast<std::size_t>(block.bit_planes));
  for (const int p : planes) {
    std::optional<t1::EncodedBlock>& slot = candidates.by_plane[static_cast<std::size_t>(p)];
    if (!slot) slot = ht::encode_ht_block(block, 31, p, t1::Distortion::Measured, passes);
  }
  candidates.skipped = false;
}

t1::EncodedBlock truncation_points(HtCandidates& candidates, int bit_planes, double energy) {
  t1::EncodedBlock out;
  out.bit_planes = bit_planes;
  out.energy = energy;
  out.stopped_early = candidates.skipped;
  // The points kept, highest plane first, as a stack: a new one no longer than the top's leaves
  // the top dominated (as many bytes or fewer, and it codes more).
  struct Kept {
    HtPoint point;
    std::size_t length;
    double decrease;  // from nothing to this point
  };
  std::vector<Kept> kept;
  for (int p = static_cast<int>(candidates.by_plane.size()) - 1; p >= 0; --p) {
    const auto& candidate = candidates.by_plane[static_cast<std::size_t>(p)];
    if (!candidate) continue;
    double decrease = 0;
    for (std::size_t j = 0; j < candidate->passes.size(); ++j) {
      const t1::PassInfo& pass = candidate->passes[j];
      decrease += pass.distortion_decrease;
      if (j > 0 && pass.length == candidate->passes[j - 1].length) continue;
      while (!kept.empty() && kept.back().length >= pass.length) kept.pop_back();
      kept.push_back(Kept{HtPoint{p, static_cast<int>(j) + 1}, pass.length, decrease});
    }
  }
  candidates.points.clear();
  double decreased = 0;
  for (const Kept& k : kept) {
    candidates.points.push_back(k.point);
    out.passes.push_back(t1::PassInfo{k.length, k.decrease - decreased, true});
    decreased = k.decrease;
  }
  return out;
}

void sync_missing_msbs(HtCandidates& candidates, const t1::EncodedBlock& points) {
  for (std::size_t p = 0; p < candidates.by_plane.size(); ++p)
    if (candidates.by_plane[p])
      candidates.by_plane[p]->missing_msbs = points.missing_msbs + points.bit_planes - 1 - static_cast<int>(p);
}

int ebcot_equivalent_passes(const HtCandidates& candidates, int bit_planes, int passes) {
  if (passes == 0) return 0;
  // EBCOT's pass 0 is the cleanup of the top plane, and each plane below adds three passes:
  // significance propagation, magnitude refinement, cleanup.
  const HtPoint& point = candidates.point(passes);
  return 3 * (bit_planes - 1 - point.plane) + point.passes;
}

}  // namespace codec
