#include "block_decoder.h"

#include <algorithm>
#include <array>
#include <vector>

#include "codec/decoder/decoder.h"
#include "codec/t1/stripe_columns.h"
#include "mq_decoder.h"
#include "simd_dispatch/scalar_clones.h"

namespace codec::dec {

namespace {

// The decoder walks a code-block exactly as the encoder's passes (codec/t1/src/coding_passes.cpp)
// do: one state word per stripe column (codec/t1/stripe_columns.h) holding the column's own
// significance, sign, visited and refined bits and its neighbours' significance, so that a whole
// column is skipped or run-length decoded after one load and every context is a table lookup.
namespace column = t1::column;

using Contexts = std::array<MqDecoderContext, t1::kContextCount>;

// D.4 (Table D.7): initial states; UNIFORM 46, run-length 3, zero coding's all-quiet context 4,
// every MPS 0.
void reset(Contexts& cx) {
  cx.fill(mq_context(0, 0));
  cx[0] = mq_context(4, 0);
  cx[t1::kRunLengthContext] = mq_context(3, 0);
  cx[t1::kUniformContext] = mq_context(46, 0);
}

const t1::ZeroCodingTable& zero_coding_table(BandOrientation o) {
  switch (o) {
    case BandOrientation::HL:
      return t1::kZeroCodingHl;
    case BandOrientation::HH:
      return t1::kZeroCodingHh;
    default:
      return t1::kZeroCodingLlLh;
  }
}

// Where a pass's decisions come from: the MQ decoder with their contexts, or raw bits (D.6). The
// pass logic is written once over these two. The MQ decisions take MqDecoder::decode_even, which
// has no branch on the decision (it says why); the cleanup's run-length decisions, nearly all
// alike, take decode() directly.
struct MqSymbols {
  MqDecoder& mq;
  Contexts& cx;

  int decision(int context) { return mq.decode_even(cx[static_cast<std::size_t>(context)]); }
  // Table D.3 through t1::kSignTable: the decoded bit is the sign XOR the prediction.
  unsigned sign(unsigned sign_index) {
    const std::uint8_t entry = t1::kSignTable[sign_index];
    return static_cast<unsigned>(mq.decode_even(cx[entry >> 1u])) ^ (entry & 1u);
  }
};

struct RawSymbols {
  RawDecoder& raw;

  int decision(int /*context*/) { return raw.bit(); }
  unsigned sign(unsigned /*sign_index*/) { return static_cast<unsigned>(raw.bit()); }  // D.6: as is
};

// A code-block's stripe column words, bordered by one column left and right and one stripe above
// and below so that make_significant may tell its neighbours without bounds checks. One buffer
// per thread, reused from block to block.
struct ColumnGrid {
  std::uint32_t* origin;  // the word of column 0 of stripe 0
  std::ptrdiff_t stride;  // words from one stripe to the next
};

ColumnGrid clear_column_grid(int width, int height) {
  thread_local std::vector<std::uint32_t> words;
  const std::ptrdiff_t stride = width + 2;
  const std::size_t size = static_cast<std::size_t>(stride) * static_cast<std::size_t>((height + 3) / 4 + 2);
  words.assign(size, 0);
  return ColumnGrid{words.data() + stride + 1, stride};
}

// `Value` holds the decoded coefficients: int32 for up to kMaxTopPlane + 1 bit-planes, int64 for
// the deeper blocks of samples over 31 bits (or large ROI shifts). kWidth is the block's width when
// known at compile time (0: any): the common 64-wide block then has constant row offsets, column
// strides and loop bounds.
template <class Value, int kWidth = 0>
class BlockDecoder {
 public:
  BlockDecoder(int w, int h, BandOrientation o, const t1::BlockStyle& style, std::span<Value> out)
      : w_(w), h_(h), grid_(clear_column_grid(w, h)), zc_(zero_coding_table(o)), style_(style), out_(out.data()) {
    reset(cx_);
  }

  void run(const BlockCodewords& block) {
    std::size_t segment = 0, segment_offset = 0;
    int passes_left_in_segment = 0;
    bool raw = false;
    for (int k = 0; k < block.passes; ++k) {
      const int plane = block.top_plane - (k + 2) / 3;
      if (plane < 0) break;                       // more passes than bit-planes: a malformed header; stop here
      const int type = k == 0 ? 2 : (k - 1) % 3;  // 0 significance, 1 refinement, 2 cleanup
      if (passes_left_in_segment == 0) {
        if (segment >= block.segments.size()) break;
        const Segment& s = block.segments[segment++];
        const std::size_t end = std::min(block.data.size(), segment_offset + s.bytes);
        const auto bytes = block.data.subspan(std::min(segment_offset, end), end - std::min(segment_offset, end));
        segment_offset = end;
        passes_left_in_segment = s.passes;
        // D.6: with bypass, significance and refinement passes after the first four bit-planes
        // (pass index 10 on) are raw; the segmentation puts them in segments of their own.
        raw = style_.bypass && k >= 10 && type != 2;
        if (raw)
          raw_.start(bytes);
        else
          mq_.start(bytes);
      }
      if (type == 0) {
        if (raw)
          significance_pass(plane, RawSymbols{raw_});
        else
          significance_pass_mq(plane);
      } else if (type == 1) {
        if (raw)
          refinement_pass(plane, RawSymbols{raw_});
        else
          refinement_pass_mq(plane);
      } else {
        cleanup_pass(plane);
      }
      --passes_left_in_segment;
      if (style_.reset) reset(cx_);  // D.4: contexts reset at the end of each pass
    }
  }

 private:
  // The MQ passes decode with a local copy of the decoder (written back after) that the compiler
  // keeps in registers; `flatten` inlines everything into the pass for that to work. Each is also
  // built for x86-64-v3 (simd_dispatch/scalar_clones.h): a lossless 2048x2048 decode on 1 thread of
  // an AMD EPYC took 8-10 % less time (2026-11-28).
  [[gnu::flatten, GPUJ2K_X86_64_V3_CLONES]] void significance_pass_mq(int plane) {
    MqDecoder mq = mq_;
    significance_pass(plane, MqSymbols{mq, cx_});
    mq_ = mq;
  }
  [[gnu::flatten, GPUJ2K_X86_64_V3_CLONES]] void refinement_pass_mq(int plane) {
    MqDecoder mq = mq_;
    refinement_pass(plane, MqSymbols{mq, cx_});
    mq_ = mq;
  }

  // Records that row r of the column at `w` turned significant with the given sign: the column
  // words (its own, `word`, held by the pass until it leaves the column), and the value at the
  // middle of [2^plane, 2^(plane+1)), doubled.
  void become_significant(std::uint32_t& word, std::uint32_t* w, int r, Value* value, unsigned negative, int plane) {
    column::make_significant(word, w, stride(), r, negative, style_.vertically_causal);
    const Value magnitude = Value{3} << plane;  // 1.5 * 2^plane, doubled
    *value = negative ? -magnitude : magnitude;
  }

  // D.3.1 on row r of the column at `w`, whose word the pass holds in `word` (`column_top` its row 0
  // in the output): an insignificant sample with at least one significant neighbour.
  template <class Symbols>
  [[gnu::always_inline]] void significance_row(std::uint32_t& word, std::uint32_t* w, int r, Value* column_top,
                                               int plane, Symbols& s) {
    const std::uint32_t around = word >> (3 * r);  // as the rows above left it
    if ((around & column::kCentre) || !(around & column::kNeighbours)) return;
    word |= column::visited(r);
    if (s.decision(zc_[around & column::kNeighbourhood]))
      become_significant(word, w, r, column_top + r * width(), s.sign(column::sign_index(word, w, r)), plane);
  }

  // D.3.1: insignificant samples with at least one significant neighbour. A full stripe's four
  // rows are written out, so that each row's shifts and masks are constants.
  template <class Symbols>
  void significance_pass(int plane, Symbols s) {
    for (int y0 = 0; y0 < h_; y0 += 4) {
      const int rows = std::min(4, h_ - y0);
      std::uint32_t* words = grid_.origin + (y0 / 4) * stride();
      Value* top = out_ + static_cast<std::ptrdiff_t>(y0) * width();
      if (rows == 4)
        significance_stripe<true>(words, top, 4, plane, s);
      else
        significance_stripe<false>(words, top, rows, plane, s);
    }
  }

  // One stripe of the significance pass; a full stripe (known at compile time, not tested per
  // column) has its four rows written out.
  template <bool kFull, class Symbols>
  [[gnu::always_inline]] void significance_stripe(std::uint32_t* words, Value* top, int rows, int plane, Symbols& s) {
    for (int x = 0; x < width(); ++x) {
      std::uint32_t* w = words + x;
      // The column's word in a register for its rows, stored once: only this column changes it
      // (a new significance tells the neighbouring columns' words, never this one's).
      std::uint32_t word = *w;
      if ((word & column::kWindow) == 0) continue;  // no significant neighbour anywhere
      if constexpr (kFull) {
        significance_row(word, w, 0, top + x, plane, s);
        significance_row(word, w, 1, top + x, plane, s);
        significance_row(word, w, 2, top + x, plane, s);
        significance_row(word, w, 3, top + x, plane, s);
      } else {
        for (int r = 0; r < rows; ++r) significance_row(word, w, r, top + x, plane, s);
      }
      *w = word;
    }
  }

  // D.3.3 on row r of a column whose word is `word` (`column_top` its row 0 in the output): the
  // refinement bit of a sample significant before this bit-plane, context by Table D.4.
  template <class Symbols>
  [[gnu::always_inline]] static void refine_row(std::uint32_t word, int r, Value* column_top, Value half, Symbols& s,
                                                int width) {
    const int bit = s.decision(t1::refinement_context(word, r));
    // The interval halves: its middle moves up or down by a quarter of the old width.
    Value& v = column_top[r * width];
    const Value step = bit ? half : -half;
    v += v < 0 ? -step : step;
  }

  // D.3.3: samples significant before this bit-plane; context by Table D.4.
  template <class Symbols>
  void refinement_pass(int plane, Symbols s) {
    const Value half = Value{1} << plane;
    for (int y0 = 0; y0 < h_; y0 += 4) {
      std::uint32_t* words = grid_.origin + (y0 / 4) * stride();
      Value* top = out_ + static_cast<std::ptrdiff_t>(y0) * width();
      for (int x = 0; x < width(); ++x) {
        const std::uint32_t word = words[x];  // refinement changes no significance: one load does
        // None significant, at low rates most columns: skipped before the due rows are worked out.
        if ((word & column::kSelfAll) == 0) continue;
        // Significant before this plane: significant, and not made so by this plane's first pass.
        const unsigned due = column::significant_rows(word) & ~(word >> 24) & 0xFu;
        if (due == 0) continue;
        // The four rows written out: constant shifts and masks in each.
        if (due & 1u) refine_row(word, 0, top + x, half, s, width());
        if (due & 2u) refine_row(word, 1, top + x, half, s, width());
        if (due & 4u) refine_row(word, 2, top + x, half, s, width());
        if (due & 8u) refine_row(word, 3, top + x, half, s, width());
        words[x] = word | due * column::refined(0);  // refined(r) = refined(0) << r, for each due row r
      }
    }
  }

  // D.3.4 on row r of the column at `w`, whose word the pass holds in `word` (`column_top` its row 0
  // in the output), outside run-length mode: a sample neither significant nor coded by this
  // bit-plane's significance pass.
  [[gnu::always_inline]] void cleanup_row(std::uint32_t& word, std::uint32_t* w, int r, Value* column_top, int plane,
                                          MqSymbols& s) {
    if (word & (column::self(r) | column::visited(r))) return;
    if (s.decision(zc_[(word >> (3 * r)) & column::kNeighbourhood]))
      become_significant(word, w, r, column_top + r * width(), s.sign(column::sign_index(word, w, r)), plane);
  }

  // One stripe of the cleanup pass; only a full stripe (known at compile time) may be run-length
  // decoded (D.3.4), and has its rows written out.
  template <bool kFull>
  [[gnu::always_inline]] void cleanup_stripe(std::uint32_t* words, Value* top, int rows, int plane, MqDecoder& mq,
                                             MqSymbols& s) {
    for (int x = 0; x < width(); ++x) {
      std::uint32_t* w = words + x;
      std::uint32_t word = *w;  // in a register for the column's rows, as in the significance pass
      if constexpr (kFull) {
        int r = 0;
        // Run-length mode: none of the four significant or visited, and all with the all-zero
        // neighbourhood (zero-coding context 0 in every orientation). Tested first: at low rates
        // most columns are such, and this test is the cheaper one.
        if ((word & (column::kWindow | column::kVisitedAll)) == 0) {
          if (!mq.decode(cx_[t1::kRunLengthContext])) continue;  // four insignificant samples
          r = mq.decode(cx_[t1::kUniformContext]) << 1;
          r |= mq.decode(cx_[t1::kUniformContext]);
          become_significant(word, w, r, top + x + r * width(), s.sign(column::sign_index(word, w, r)), plane);
          ++r;
        } else if (column::all_rows_significant_or_visited(word)) {
          // Each of the four significant or coded by the significance pass: only the marks to clear.
          *w = word & ~column::kVisitedAll;
          continue;
        }
        switch (r) {  // the rows from r on written out: constant shifts and masks
          case 0:
            cleanup_row(word, w, 0, top + x, plane, s);
            [[fallthrough]];
          case 1:
            cleanup_row(word, w, 1, top + x, plane, s);
            [[fallthrough]];
          case 2:
            cleanup_row(word, w, 2, top + x, plane, s);
            [[fallthrough]];
          case 3:
            cleanup_row(word, w, 3, top + x, plane, s);
            break;
          default:
            break;
        }
      } else {
        for (int r = 0; r < rows; ++r) cleanup_row(word, w, r, top + x, plane, s);
      }
      *w = word & ~column::kVisitedAll;
    }
  }

  // D.3.4: everything the significance pass left, with run-length decoding of quiet stripe
  // columns; then the segmentation symbol of D.5.
  [[gnu::flatten, GPUJ2K_X86_64_V3_CLONES]] void cleanup_pass(int plane) {
    MqDecoder mq = mq_;
    MqSymbols s{mq, cx_};
    for (int y0 = 0; y0 < h_; y0 += 4) {
      const int rows = std::min(4, h_ - y0);
      std::uint32_t* words = grid_.origin + (y0 / 4) * stride();
      Value* top = out_ + static_cast<std::ptrdiff_t>(y0) * width();
      if (rows == 4)
        cleanup_stripe<true>(words, top, 4, plane, mq, s);
      else
        cleanup_stripe<false>(words, top, rows, plane, mq, s);
    }
    if (style_.segmentation_symbols) {
      // 1010 in the UNIFORM context; a mismatch marks a corrupt pass, but the data decoded so far
      // stands (the decoder has no better value to put in its place).
      for (int i = 0; i < 4; ++i) mq.decode(cx_[t1::kUniformContext]);
    }
    mq_ = mq;
  }

  // The block's width: kWidth where given, so that the passes' offsets are constants.
  int width() const { return kWidth > 0 ? kWidth : w_; }
  std::ptrdiff_t stride() const { return kWidth > 0 ? kWidth + 2 : grid_.stride; }

  int w_, h_;
  ColumnGrid grid_;
  const t1::ZeroCodingTable& zc_;
  t1::BlockStyle style_;
  Value* out_;
  Contexts cx_{};
  MqDecoder mq_;
  RawDecoder raw_;
};

template <class Value>
void decode_code_block(const BlockCodewords& block, int width, int height, BandOrientation orientation,
                       const t1::BlockStyle& style, std::span<Value> out, int max_top_plane) {
  std::fill(out.begin(), out.end(), 0);
  if (block.passes <= 0 || width <= 0 || height <= 0) return;
  if (block.top_plane > max_top_plane)
    throw DecodeError("a code-block has " + std::to_string(block.top_plane + 1) +
                      " magnitude bit-planes; this decoder handles at most " + std::to_string(max_top_plane + 1));
  // 64 wide, the default and most common code-block width, with its offsets as constants: 1.7 % fewer
  // instructions in a lossless 1024x1024 decode (892.0 M to 876.4 M, callgrind, 2026-11-28).
  if (width == 64) {
    BlockDecoder<Value, 64> decoder(width, height, orientation, style, out);
    decoder.run(block);
  } else {
    BlockDecoder<Value> decoder(width, height, orientation, style, out);
    decoder.run(block);
  }
}

}  // namespace

void decode_code_block(const BlockCodewords& block, int width, int height, BandOrientation orientation,
                       const t1::BlockStyle& style, std::span<std::int32_t> out) {
  decode_code_block(block, width, height, orientation, style, out, kMaxTopPlane);
}

void decode_code_block(const BlockCodewords& block, int width, int height, BandOrientation orientation,
                       const t1::BlockStyle& style, std::span<std::int64_t> out) {
  decode_code_block(block, width, height, orientation, style, out, kMaxWideTopPlane);
}

}  // namespace codec::dec
