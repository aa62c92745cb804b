#include "coding_passes.h"

#include "distortion.h"
#include "neighbourhood.h"

namespace codec::t1 {

namespace {

// How a pass's decisions reach the codeword: through the MQ coder with their contexts, or as raw
// bits. The pass logic is written once over these two.
struct MqSymbols {
  MqEncoder& mq;
  ContextSet& cx;

  void decision(int bit, int context) { mq.encode(bit, cx[static_cast<std::size_t>(context)]); }
  void sign(unsigned negative, std::uint16_t flags) {
    const std::uint8_t entry = kSignTable[sign_table_index(flags)];
    mq.encode(static_cast<int>(negative ^ (entry & 1u)), cx[entry >> 1]);
  }
};

struct RawSymbols {
  RawWriter& raw;

  void decision(int bit, int /*context*/) { raw.put(bit); }
  void sign(unsigned negative, std::uint16_t /*flags*/) { raw.put(static_cast<int>(negative)); }  // D.6: as is
};

inline int bit_at(std::uint32_t magnitude, int plane) { return static_cast<int>((magnitude >> plane) & 1u); }

// Codes the sign of a coefficient whose significance bit just came out 1, then records it.
template <class Symbols>
inline std::int64_t become_significant(const BlockView& v, std::ptrdiff_t i, int row, const PlaneDistortion& d,
                                       Symbols& s) {
  std::uint16_t* f = v.flags + i;
  const unsigned negative = static_cast<unsigned>(*f >> 15);
  s.sign(negative, *f);
  make_significant(f, v.stride, negative, v.causal && row == 0);
  return d.significance_gain(v.fine[i]);
}

// D.3.1: insignificant coefficients with at least one significant neighbour.
template <class Symbols>
double significance_pass_impl(const BlockView v, int plane, const ZeroCodingTable& zc, Symbols s) {
  const PlaneDistortion d(plane + v.fine_bits);
  DistortionSum gain(plane + v.fine_bits, v.fine_bits);
  // A column has no candidate if all four are significant, or none has a significant neighbour
  // (then none of them becomes significant either, so the column stays as it is).
  auto worth_visiting = [](ColumnSummary c) { return !(c.all & kSig) && (c.any & kNeighbourMask); };
  for_each_in_scan_order(v, worth_visiting, [&](std::ptrdiff_t i, int row) {
    std::uint16_t& f = v.flags[i];
    if ((f & kSig) || !(f & kNeighbourMask)) return;
    const int bit = bit_at(v.magnitude[i], plane);
    s.decision(bit, zc[f & kNeighbourMask]);
    f |= kVisited;
    if (bit) gain.add(become_significant(v, i, row, d, s));
  });
  return gain.value();
}

// D.3.3: coefficients significant before this bit-plane; context by Table D.4.
template <class Symbols>
double refinement_pass_impl(const BlockView v, int plane, Symbols s) {
  const PlaneDistortion d(plane + v.fine_bits);
  DistortionSum gain(plane + v.fine_bits, v.fine_bits);
  auto worth_visiting = [](ColumnSummary c) { return (c.any & kSig) != 0; };
  for_each_in_scan_order(v, worth_visiting, [&](std::ptrdiff_t i, int /*row*/) {
    std::uint16_t& f = v.flags[i];
    if ((f & (kSig | kVisited)) != kSig) return;
    s.decision(bit_at(v.magnitude[i], plane), refinement_context(f));
    f |= kRefined;
    gain.add_units(d.refinement_units(v.fine[i]));
  });
  return gain.value();
}

// Which of the four rows of a run-length column holds the first 1 at `plane`; 4 if none.
inline int first_one_in_column(const BlockView& v, std::ptrdiff_t i, int plane) {
  for (int row = 0; row < 4; ++row, i += v.stride)
    if (bit_at(v.magnitude[i], plane)) return row;
  return 4;
}

}  // namespace

// The arithmetic-coded passes work on a local copy of the coder (and of the view) that the
// compiler can keep in registers for the whole pass (see MqEncoder::byte_out). `flatten` makes
// sure everything is inlined early enough for that to happen.
[[gnu::flatten]] double significance_pass(const BlockView& v, int plane, const ZeroCodingTable& zc, ContextSet& cx, MqEncoder& mq) {
  MqEncoder coder = mq;
  const double gain = significance_pass_impl(BlockView(v), plane, zc, MqSymbols{coder, cx});
  mq = coder;
  return gain;
}

double significance_pass_raw(const BlockView& v, int plane, RawWriter& raw) {
  return significance_pass_impl(BlockView(v), plane, kZeroCodingLlLh, RawSymbols{raw});
}

[[gnu::flatten]] double refinement_pass(const BlockView& v, int plane, ContextSet& cx, MqEncoder& mq) {
  MqEncoder coder = mq;
  const double gain = refinement_pass_impl(BlockView(v), plane, MqSymbols{coder, cx});
  mq = coder;
  return gain;
}

double refinement_pass_raw(const BlockView& v, int plane, RawWriter& raw) {
  return refinement_pass_impl(BlockView(v), plane, RawSymbols{raw});
}

// D.3.4: everything the significance pass left, with run-length coding of quiet stripe columns.
[[gnu::flatten]] double cleanup_pass(const BlockView& view, int plane, const ZeroCodingTable& zc, ContextSet& cx, MqEncoder& coder) {
  const BlockView v = view;
  MqEncoder mq = coder;
  MqSymbols s{mq, cx};
  const std::ptrdiff_t stride = v.stride;
  const PlaneDistortion d(plane + v.fine_bits);
  DistortionSum gain(plane + v.fine_bits, v.fine_bits);
  for (int y0 = 0; y0 < v.height; y0 += 4) {
    const int rows = std::min(4, v.height - y0);
    for (int x = 0; x < v.width; ++x) {
      const std::ptrdiff_t top = v.index(x, y0);
      int row = 0;
      if (rows == 4) {
        // Run-length mode: a full column of four coefficients, none significant or visited, and
        // all with the all-zero neighbourhood (zero-coding context 0 in every orientation).
        std::uint16_t* f = v.flags + top;
        const unsigned f0 = f[0], f1 = f[stride], f2 = f[2 * stride], f3 = f[3 * stride];
        // Nothing to code when each of the four is significant or was coded by the significance
        // pass (kVisited sits one bit above kSig); only the marks need clearing.
        static_assert(kVisited == kSig << 1);
        if ((f0 | f0 >> 1) & (f1 | f1 >> 1) & (f2 | f2 >> 1) & (f3 | f3 >> 1) & kSig) {
          for (int k = 0; k < 4; ++k) f[k * stride] = static_cast<std::uint16_t>(f[k * stride] & ~kVisited);
          continue;
        }
        const unsigned any = f0 | f1 | f2 | f3;
        if (!(any & (kSig | kVisited | kNeighbourMask))) {
          row = first_one_in_column(v, top, plane);
          if (row == 4) {
            mq.encode(0, cx[kRunLengthContext]);
            continue;
          }
          mq.encode(1, cx[kRunLengthContext]);
          mq.encode(row >> 1, cx[kUniformContext]);
          mq.encode(row & 1, cx[kUniformContext]);
          gain.add(become_significant(v, top + row * stride, row, d, s));
          ++row;
        }
      }
      for (std::ptrdiff_t i = top + row * stride; row < rows; ++row, i += stride) {
        std::uint16_t& f = v.flags[i];
        if (f & (kSig | kVisited)) {
          f = static_cast<std::uint16_t>(f & ~kVisited);
          continue;
        }
        const int bit = bit_at(v.magnitude[i], plane);
        mq.encode(bit, cx[zc[f & kNeighbourMask]]);
        if (bit) gain.add(become_significant(v, i, row, d, s));
      }
    }
  }
  coder = mq;
  return gain.value();
}

}  // namespace codec::t1
