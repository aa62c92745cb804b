#include "coding_passes.h"

#include <algorithm>
#include <bit>

#include "column_masks_simd.h"
#include "distortion.h"
#include "codec/t1/stripe_columns.h"
#include "simd_dispatch/scalar_clones.h"

namespace codec::t1 {

namespace {

// How a pass's decisions reach the codeword: through the MQ coder with their contexts, or as raw
// bits. The pass logic is written once over these two.
struct MqSymbols {
  MqEncoder& mq;
  ContextSet& cx;

  void decision(int bit, int context) { mq.encode(bit, cx[static_cast<std::size_t>(context)]); }
  void sign(unsigned negative, unsigned sign_index) {
    const std::uint8_t entry = kSignTable[sign_index];
    mq.encode(static_cast<int>(negative ^ (entry & 1u)), cx[entry >> 1]);
  }
};

struct RawSymbols {
  RawWriter& raw;

  void decision(int bit, int /*context*/) { raw.put(bit); }
  void sign(unsigned negative, unsigned /*sign_index*/) { raw.put(static_cast<int>(negative)); }  // D.6: as is
};

template <bool kMeasure>
inline void add_gain(DistortionSum& sum, std::int64_t gain) {
  if constexpr (kMeasure) sum.add(gain);
}

inline int bit_at(std::uint32_t magnitude, int plane) { return static_cast<int>((magnitude >> plane) & 1u); }

// Calls row(r, i) for the rows r of a column from `first` on, i the coefficient's index; unrolled
// for a full column, where a four-trip loop would cost a mispredicted exit every time.
template <class Row>
inline void for_each_row(const BlockView& v, std::ptrdiff_t top, int first, int rows, Row&& row) {
  if (rows == 4 && first == 0) {
    row(0, top);
    row(1, top + v.stride);
    row(2, top + 2 * v.stride);
    row(3, top + 3 * v.stride);
    return;
  }
  for (int r = first; r < rows; ++r) row(r, top + r * v.stride);
}

// Codes the sign of the coefficient in row r of the column at `w` (index i) whose significance bit
// just came out 1, then records it.
template <bool kMeasure, class Symbols>
inline std::int64_t become_significant(const BlockView& v, std::uint32_t* w, std::ptrdiff_t i, int r,
                                       const PlaneDistortion& d, Symbols& s) {
  const unsigned negative = static_cast<unsigned>(v.sign[i] >> 15);
  s.sign(negative, column::sign_index(w, r));
  column::make_significant(w, v.column_stride, r, negative, v.causal);
  if constexpr (kMeasure) return d.significance_gain(v.fine[i]);
  return 0;
}

// Calls visit(k, x, n) for the columns x = x0 + k of a stripe, in chunks of n <= 64 (simd::kMaskColumns),
// whose bit is set in the chunk's mask(x0, n); visit returns bits to add to the rest of the chunk's
// mask (a column a pass has just made busy). A quiet column costs no load of its own.
template <class Mask, class Visit>
inline void for_each_masked_column(int width, Mask&& mask, Visit&& visit) {
  for (int x0 = 0; x0 < width; x0 += static_cast<int>(simd::kMaskColumns)) {
    const int n = std::min(static_cast<int>(simd::kMaskColumns), width - x0);
    for (std::uint64_t todo = mask(x0, n); todo != 0;) {
      const int k = std::countr_zero(todo);
      todo &= todo - 1;
      todo |= visit(k, x0 + k, n);
    }
  }
}

// The bit of the column after column k of a chunk of n, which a coefficient that column k has made
// significant brings into its window; 0 past the chunk (the next chunk's mask is made after).
inline std::uint64_t next_column_bit(int k, int n) { return k + 1 < n ? std::uint64_t{2} << k : 0; }

// D.3.1: insignificant coefficients with at least one significant neighbour.
template <bool kMeasure, class Symbols>
double significance_pass_impl(const BlockView v, int plane, const ZeroCodingTable& zc, Symbols s) {
  const PlaneDistortion d(plane + v.fine_bits);
  DistortionSum gain(plane + v.fine_bits, v.fine_bits);
  for (int y0 = 0; y0 < v.height; y0 += 4) {
    const int rows = std::min(4, v.height - y0);
    std::uint32_t* words = v.columns + (y0 / 4) * v.column_stride;
    const std::ptrdiff_t stripe_top = v.index(0, y0);
    // Columns with nothing significant in their window have no candidate; a column that becomes
    // significant here gives its eastern neighbour one, which joins the walk.
    for_each_masked_column(
        v.width,
        [&](int x0, int n) { return simd::columns_with(words + x0, static_cast<std::size_t>(n), column::kWindow); },
        [&](int k, int x, int n) {
          std::uint32_t* w = words + x;
          bool any = false;
          for_each_row(v, stripe_top + x, 0, rows, [&](int r, std::ptrdiff_t i) {
            const std::uint32_t around = *w >> (3 * r);  // reloaded: the row above may just have changed it
            if ((around & column::kCentre) || !(around & column::kNeighbours)) return;
            const int bit = bit_at(v.magnitude[i], plane);
            s.decision(bit, zc[around & column::kNeighbourhood]);
            *w |= column::visited(r);
            if (bit) {
              any = true;
              add_gain<kMeasure>(gain, become_significant<kMeasure>(v, w, i, r, d, s));
            }
          });
          return any ? next_column_bit(k, n) : 0;
        });
  }
  return gain.value();
}

// D.3.3: coefficients significant before this bit-plane; context by Table D.4.
template <bool kMeasure, class Symbols>
double refinement_pass_impl(const BlockView v, int plane, Symbols s) {
  const PlaneDistortion d(plane + v.fine_bits);
  DistortionSum gain(plane + v.fine_bits, v.fine_bits);
  for (int y0 = 0; y0 < v.height; y0 += 4) {
    std::uint32_t* words = v.columns + (y0 / 4) * v.column_stride;
    const std::ptrdiff_t stripe_top = v.index(0, y0);
    // Only columns with a significant row (only rows in the block are); refinement makes none.
    for_each_masked_column(
        v.width,
        [&](int x0, int n) { return simd::columns_with(words + x0, static_cast<std::size_t>(n), column::kSelfAll); },
        [&](int, int x, int) -> std::uint64_t {
          std::uint32_t* w = words + x;
          const std::uint32_t word = *w;  // refinement changes no significance: one load does
          // Significant before this plane: significant, and not made so by this plane's first pass.
          const unsigned due = column::significant_rows(word) & ~(word >> 24) & 0xFu;
          std::uint32_t refined = 0;
          // The due rows one by one, lowest first (scan order): a branch per row coded rather than a
          // poorly predicted one per row of the column.
          for (unsigned left = due; left != 0; left &= left - 1) {
            const int r = std::countr_zero(left);
            const std::ptrdiff_t i = stripe_top + x + r * v.stride;
            s.decision(bit_at(v.magnitude[i], plane), refinement_context(word, r));
            refined |= column::refined(r);
            if constexpr (kMeasure) gain.add_units(d.refinement_units(v.fine[i]));
          }
          *w = word | refined;
          return 0;
        });
  }
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
// sure everything is inlined early enough for that to happen. Each is also built for x86-64-v3
// (simd_dispatch/scalar_clones.h): 2.5 % fewer instructions in a lossless 1024x1024 encode, and a
// 2048x2048 one on 2 threads of an AMD EPYC 5-7 % faster (2026-11-28); the same codewords.
template <bool kMeasure>
[[gnu::flatten, GPUJ2K_X86_64_V3_CLONES]] double significance_pass(const BlockView& v, int plane,
                                                                   const ZeroCodingTable& zc, ContextSet& cx,
                                                                   MqEncoder& mq) {
  MqEncoder coder = mq;
  const double gain = significance_pass_impl<kMeasure>(BlockView(v), plane, zc, MqSymbols{coder, cx});
  mq = coder;
  return gain;
}

template <bool kMeasure>
double significance_pass_raw(const BlockView& v, int plane, RawWriter& raw) {
  return significance_pass_impl<kMeasure>(BlockView(v), plane, kZeroCodingLlLh, RawSymbols{raw});
}

template <bool kMeasure>
[[gnu::flatten, GPUJ2K_X86_64_V3_CLONES]] double refinement_pass(const BlockView& v, int plane, ContextSet& cx,
                                                                 MqEncoder& mq) {
  MqEncoder coder = mq;
  const double gain = refinement_pass_impl<kMeasure>(BlockView(v), plane, MqSymbols{coder, cx});
  mq = coder;
  return gain;
}

template <bool kMeasure>
double refinement_pass_raw(const BlockView& v, int plane, RawWriter& raw) {
  return refinement_pass_impl<kMeasure>(BlockView(v), plane, RawSymbols{raw});
}

// D.3.4: everything the significance pass left, with run-length coding of quiet stripe columns.
template <bool kMeasure>
[[gnu::flatten, GPUJ2K_X86_64_V3_CLONES]] double cleanup_pass(const BlockView& view, int plane,
                                                              const ZeroCodingTable& zc, ContextSet& cx,
                                                              MqEncoder& coder) {
  const BlockView v = view;
  MqEncoder mq = coder;
  MqSymbols s{mq, cx};
  const PlaneDistortion d(plane + v.fine_bits);
  DistortionSum gain(plane + v.fine_bits, v.fine_bits);
  for (int y0 = 0; y0 < v.height; y0 += 4) {
    const int rows = std::min(4, v.height - y0);
    std::uint32_t* words = v.columns + (y0 / 4) * v.column_stride;
    const std::uint32_t* magnitudes = v.column_magnitudes + (y0 / 4) * v.column_stride;
    const std::ptrdiff_t stripe_top = v.index(0, y0);
    // Run-length mode (a full column with none of the four significant or visited, all with the
    // all-zero neighbourhood: zero-coding context 0 in every orientation) with no 1 at this plane:
    // one symbol 0. Coding such a column changes nothing, so a chunk's quiet columns are found at
    // once (simd::quiet_columns) and each run of them coded in one call. A column that makes a
    // coefficient significant puts it in its eastern neighbour's window: that one is no longer quiet.
    for (int x0 = 0; x0 < v.width; x0 += static_cast<int>(simd::kMaskColumns)) {
      const int n = std::min(static_cast<int>(simd::kMaskColumns), v.width - x0);
      std::uint64_t quiet = rows == 4 ? simd::quiet_columns(words + x0, magnitudes + x0, static_cast<std::size_t>(n),
                                                            column::kWindow | column::kVisitedAll, plane)
                                      : 0;
      for (int k = 0; k < n; ++k) {
        if ((quiet >> k) & 1u) {
          const int run = std::countr_one(quiet >> k);
          mq.encode_zeros(cx[kRunLengthContext], run);
          k += run - 1;
          continue;
        }
        const int x = x0 + k;
        std::uint32_t* w = words + x;
        const std::ptrdiff_t top = stripe_top + x;
        const std::uint32_t before = *w;
        int r = 0;
        if (rows == 4) {
          // Nothing to code when each of the four is significant or was coded by the significance
          // pass; only the marks need clearing.
          if (column::all_rows_significant_or_visited(before)) {
            *w = before & ~column::kVisitedAll;
            continue;
          }
          // Run-length mode with a 1 in the column: the row of the first one.
          if ((before & (column::kWindow | column::kVisitedAll)) == 0) {
            r = first_one_in_column(v, top, plane);
            mq.encode(1, cx[kRunLengthContext]);
            mq.encode(r >> 1, cx[kUniformContext]);
            mq.encode(r & 1, cx[kUniformContext]);
            add_gain<kMeasure>(gain, become_significant<kMeasure>(v, w, top + r * v.stride, r, d, s));
            ++r;
          }
        }
        for_each_row(v, top, r, rows, [&](int row, std::ptrdiff_t i) {
          const std::uint32_t word = *w;
          if (word & (column::self(row) | column::visited(row))) return;
          const int bit = bit_at(v.magnitude[i], plane);
          mq.encode(bit, cx[zc[(word >> (3 * row)) & column::kNeighbourhood]]);
          if (bit) add_gain<kMeasure>(gain, become_significant<kMeasure>(v, w, i, row, d, s));
        });
        if ((*w ^ before) & column::kSelfAll) quiet &= ~next_column_bit(k, n);
        *w &= ~column::kVisitedAll;
      }
    }
  }
  coder = mq;
  return gain.value();
}

template double significance_pass<true>(const BlockView&, int, const ZeroCodingTable&, ContextSet&, MqEncoder&);
template double significance_pass<false>(const BlockView&, int, const ZeroCodingTable&, ContextSet&, MqEncoder&);
template double significance_pass_raw<true>(const BlockView&, int, RawWriter&);
template double significance_pass_raw<false>(const BlockView&, int, RawWriter&);
template double refinement_pass<true>(const BlockView&, int, ContextSet&, MqEncoder&);
template double refinement_pass<false>(const BlockView&, int, ContextSet&, MqEncoder&);
template double refinement_pass_raw<true>(const BlockView&, int, RawWriter&);
template double refinement_pass_raw<false>(const BlockView&, int, RawWriter&);
template double cleanup_pass<true>(const BlockView&, int, const ZeroCodingTable&, ContextSet&, MqEncoder&);
template double cleanup_pass<false>(const BlockView&, int, const ZeroCodingTable&, ContextSet&, MqEncoder&);

}  // namespace codec::t1
