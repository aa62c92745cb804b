#include "dwt_gpu/address_table.h"

#include <algorithm>

namespace dwt_gpu {
namespace {

std::vector<AddressTexel> blank_row(int length, int pad) {
  return std::vector<AddressTexel>(static_cast<std::size_t>(length + 2 * pad));
}

}  // namespace

std::vector<AddressTexel> forward_row(dwt::AxisSpan span, int pad, dwt::Boundary boundary) {
  const int n = span.length, p = span.parity(), low = span.low_count();
  auto row = blank_row(n, pad);
  for (int i = 0; i < static_cast<int>(row.size()); ++i)
    row[static_cast<std::size_t>(i)].address = static_cast<float>(dwt::extend_index(i - pad, n, boundary));
  for (int e = 0; e < n; ++e) {
    AddressTexel& t = row[static_cast<std::size_t>(e + pad)];
    if (n == 1) {
      t.alpha = p ? kLoneOdd : kLoneEven;
      t.beta = 0;
    } else if (e < low) {
      t.alpha = kFirstKernel;
      t.beta = static_cast<float>(2 * e + p);
    } else {
      t.alpha = kSecondKernel;
      t.beta = static_cast<float>(2 * (e - low) + 1 - p);
    }
  }
  return row;
}

std::vector<AddressTexel> inverse_row(dwt::AxisSpan span, int pad, dwt::Boundary boundary) {
  const int n = span.length, p = span.parity(), low = span.low_count();
  auto row = blank_row(n, pad);
  for (int i = 0; i < static_cast<int>(row.size()); ++i) {
    const auto q = static_cast<int>(dwt::extend_index(i - pad, n, boundary));
    float address = -1;
    if (q >= 0) address = static_cast<float>(((q + p) & 1) == 0 ? (q - p) >> 1 : low + ((q - 1 + p) >> 1));
    row[static_cast<std::size_t>(i)].address = address;
  }
  for (int m = 0; m < n; ++m) {
    AddressTexel& t = row[static_cast<std::size_t>(m + pad)];
    t.alpha = static_cast<float>(n == 1 ? (p ? kLoneOdd : kLoneEven) : (m + p) & 1);
    t.beta = static_cast<float>(m);
  }
  return row;
}

AddressTable build_table(const std::vector<dwt::LevelGeometry>& levels, int pad, dwt::Boundary boundary, bool inverse) {
  AddressTable table;
  table.pad = pad;
  table.rows = std::max(1, 2 * static_cast<int>(levels.size()));
  for (const auto& g : levels) table.width = std::max({table.width, g.x.length + 2 * pad, g.y.length + 2 * pad});
  table.width = std::max(table.width, 1);
  table.rgba.assign(static_cast<std::size_t>(table.rows) * static_cast<std::size_t>(table.width) * 4, -1.0f);
  for (std::size_t d = 0; d < levels.size(); ++d)
    for (bool vertical : {false, true}) {
      const dwt::AxisSpan span = vertical ? levels[d].y : levels[d].x;
      const auto row = inverse ? inverse_row(span, pad, boundary) : forward_row(span, pad, boundary);
      float* out = table.rgba.data() + static_cast<std::size_t>(AddressTable::row_of(static_cast<int>(d), vertical)) *
                                           static_cast<std::size_t>(table.width) * 4;
      for (std::size_t i = 0; i < row.size(); ++i) {
        out[4 * i + 0] = row[i].address;
        out[4 * i + 1] = row[i].alpha;
        out[4 * i + 2] = row[i].beta;
        out[4 * i + 3] = 0.0f;
      }
    }
  return table;
}

}  // namespace dwt_gpu
