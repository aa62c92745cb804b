#include "dwt/band_operation.h"

#include "dwt/error.h"

namespace dwt {

std::vector<BandId> all_bands(int levels) {
  std::vector<BandId> bands;
  bands.push_back({levels, Orientation::LL});
  for (int level = levels; level >= 1; --level)
    for (Orientation o : {Orientation::HL, Orientation::LH, Orientation::HH}) bands.push_back({level, o});
  return bands;
}

LayoutRect band_rect(const std::vector<LevelGeometry>& levels, const BandId& band, int width, int height) {
  if (levels.empty()) {
    if (band.orientation != Orientation::LL) throw DwtError("a plane with no decomposition level has only LL");
    return {0, 0, width, height};
  }
  return band_rect(levels, band.level, band.orientation);
}

void apply_band_operations(PlaneSpan<float> first, PlaneSpan<const float> second, std::span<const BandOperation> ops) {
  for (const BandOperation& op : ops) {
    const bool reads_second = op.rule != BandRule::First;
    if (reads_second && (second.data == nullptr || second.width != first.width || second.height != first.height))
      throw DwtError("a band rule that combines two planes needs a second plane of the same size");
    const LayoutRect& r = op.rect;
    if (r.x < 0 || r.y < 0 || r.x + r.width > first.width || r.y + r.height > first.height)
      throw DwtError("band rectangle outside the plane");
    for (int y = r.y; y < r.y + r.height; ++y) {
      float* a = first.row(y);
      const float* b = reads_second ? second.row(y) : nullptr;
      for (int x = r.x; x < r.x + r.width; ++x) a[x] = apply_rule(op, a[x], b ? b[x] : 0.0f);
    }
  }
}

}  // namespace dwt
