#pragma once
// The tier-1 decoder as it was before the stripe-column rewrite of codec/decoder/src/block_decoder.cpp
// (per-sample byte flags, neighbours counted per sample, the MQ decoder's state in members), kept
// for t1_decoder_test as the reference the fast decoder must match bit for bit. Same interface as
// codec::dec::decode_code_block; slow on purpose, do not optimise.
#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "block_decoder.h"  // codec/decoder/src: BlockCodewords, Segment, kMaxTopPlane
#include "codec/t1/mq_states.h"

namespace t1dec_ref {

using codec::BandOrientation;
using codec::dec::BlockCodewords;
using codec::dec::kMaxTopPlane;
using codec::dec::Segment;
namespace t1 = codec::t1;

// An adaptive probability context: index into T.800 Table C.2 and the current MPS.
struct MqDecoderContext {
  std::uint8_t state = 0;
  std::uint8_t mps = 0;
};

// The MQ arithmetic decoder of T.800 C.3 (INITDEC, DECODE, RENORMD, BYTEIN; Figures C.15-C.20),
// over one codeword segment. Past the segment's end it reads 0xFF bytes: BYTEIN then sees a
// marker and feeds 1-bits, as C.3.4 prescribes, so a short or truncated segment decodes to
// something bounded instead of reading outside its bytes.
//
class MqDecoder {
 public:
  void start(std::span<const std::uint8_t> segment);
  int decode(MqDecoderContext& cx);

 private:
  std::uint8_t byte_at(std::size_t i) const { return i < data_.size() ? data_[i] : 0xFF; }
  void byte_in();
  void renormalise();

  std::span<const std::uint8_t> data_;
  std::size_t pos_ = 0;
  std::uint32_t a_ = 0, c_ = 0;
  int ct_ = 0;
};

inline void MqDecoder::renormalise() {
  // RENORMD (Figure C.18).
  do {
    if (ct_ == 0) byte_in();
    a_ <<= 1;
    c_ <<= 1;
    --ct_;
  } while ((a_ & 0x8000) == 0);
}

inline int MqDecoder::decode(MqDecoderContext& cx) {
  // DECODE (Figure C.15) with LPS_EXCHANGE (C.17) and MPS_EXCHANGE (C.16).
  const t1::MqStateRow& row = t1::kMqStates[cx.state];
  const std::uint32_t qe = row.qe;
  int d;
  a_ -= qe;
  if ((c_ >> 16) < qe) {
    if (a_ < qe) {
      d = cx.mps;
      cx.state = row.nmps;
    } else {
      d = 1 - cx.mps;
      if (row.switch_mps) cx.mps = static_cast<std::uint8_t>(1 - cx.mps);
      cx.state = row.nlps;
    }
    a_ = qe;
    renormalise();
  } else {
    c_ -= qe << 16;
    if ((a_ & 0x8000) == 0) {
      if (a_ < qe) {
        d = 1 - cx.mps;
        if (row.switch_mps) cx.mps = static_cast<std::uint8_t>(1 - cx.mps);
        cx.state = row.nlps;
      } else {
        d = cx.mps;
        cx.state = row.nmps;
      }
      renormalise();
    } else {
      d = cx.mps;
    }
  }
  return d;
}

// The raw (bypass) segments of D.6: bits MSB first, with the MSB of every byte after a 0xFF
// skipped (it is a stuffed 0). Past the end it reads 0xFF bytes.
class RawDecoder {
 public:
  void start(std::span<const std::uint8_t> segment);
  int bit();

 private:
  std::span<const std::uint8_t> data_;
  std::size_t pos_ = 0;
  std::uint8_t byte_ = 0;
  int bits_left_ = 0;
};

inline void MqDecoder::start(std::span<const std::uint8_t> segment) {
  // INITDEC (Figure C.20).
  data_ = segment;
  pos_ = 0;
  c_ = static_cast<std::uint32_t>(byte_at(0)) << 16;
  byte_in();
  c_ <<= 7;
  ct_ -= 7;
  a_ = 0x8000;
}

inline void MqDecoder::byte_in() {
  // BYTEIN (Figure C.19): a 0xFF followed by a byte above 0x8F is a marker (or the end), which
  // is never consumed; a 0xFF followed by anything else means the next byte has a stuffed bit.
  if (byte_at(pos_) == 0xFF) {
    if (byte_at(pos_ + 1) > 0x8F) {
      c_ += 0xFF00;
      ct_ = 8;
    } else {
      ++pos_;
      c_ += static_cast<std::uint32_t>(byte_at(pos_)) << 9;
      ct_ = 7;
    }
  } else {
    ++pos_;
    c_ += static_cast<std::uint32_t>(byte_at(pos_)) << 8;
    ct_ = 8;
  }
}

void RawDecoder::start(std::span<const std::uint8_t> segment) {
  data_ = segment;
  pos_ = 0;
  byte_ = 0;
  bits_left_ = 0;
}

inline int RawDecoder::bit() {
  if (bits_left_ == 0) {
    const bool after_ff = byte_ == 0xFF;
    byte_ = pos_ < data_.size() ? data_[pos_] : 0xFF;
    ++pos_;
    bits_left_ = after_ff ? 7 : 8;
  }
  --bits_left_;
  return (byte_ >> bits_left_) & 1;
}

// Context labels of T.800 Annex D: 0-8 zero coding (Table D.1), 9-13 sign (Table D.3), 14-16
// magnitude refinement (Table D.4), 17 run-length, 18 UNIFORM (D.3.4).
constexpr int kRunLength = 17;
constexpr int kUniform = 18;
constexpr int kContexts = 19;
using Contexts = std::array<MqDecoderContext, kContexts>;

// D.4 (Table D.7): initial states; UNIFORM 46, run-length 3, zero coding's all-quiet context 4.
inline void reset(Contexts& cx) {
  cx.fill(MqDecoderContext{0, 0});
  cx[0].state = 4;
  cx[kRunLength].state = 3;
  cx[kUniform].state = 46;
}

// Table D.1, for LL and LH; HL swaps h and v; HH is separate.
inline int zero_context_lh(int h, int v, int d) {
  if (h == 2) return 8;
  if (h == 1) return v >= 1 ? 7 : (d >= 1 ? 6 : 5);
  if (v == 2) return 4;
  if (v == 1) return 3;
  return d >= 2 ? 2 : d;
}
inline int zero_context_hh(int h, int v, int d) {
  const int hv = h + v;
  if (d >= 3) return 8;
  if (d == 2) return hv >= 1 ? 7 : 6;
  if (d == 1) return hv >= 2 ? 5 : (hv == 1 ? 4 : 3);
  return hv >= 2 ? 2 : hv;
}

// Per-sample state flags.
constexpr std::uint8_t kSignificant = 1;
constexpr std::uint8_t kNegative = 2;
constexpr std::uint8_t kVisited = 4;  // coded in this bit-plane's significance pass (D.3.1)
constexpr std::uint8_t kRefined = 8;  // refined at least once (Table D.4)

enum class PassType { Significance, Refinement, Cleanup };

class BlockDecoder {
 public:
  BlockDecoder(int w, int h, BandOrientation o, const t1::BlockStyle& style, std::span<std::int32_t> out)
      : w_(w),
        h_(h),
        stride_(w + 2),
        orientation_(o),
        style_(style),
        out_(out),
        flags_(static_cast<std::size_t>(w + 2) * static_cast<std::size_t>(h + 2), 0) {
    reset(cx_);
  }

  void run(const BlockCodewords& block) {
    std::size_t segment = 0, segment_offset = 0;
    int passes_left_in_segment = 0;
    bool raw = false;
    for (int k = 0; k < block.passes; ++k) {
      const int plane = block.top_plane - (k + 2) / 3;
      if (plane < 0) break;  // more passes than bit-planes: a malformed header; stop here
      const PassType type = k == 0 ? PassType::Cleanup : static_cast<PassType>((k - 1) % 3);
      if (passes_left_in_segment == 0) {
        if (segment >= block.segments.size()) break;
        const Segment& s = block.segments[segment++];
        const std::size_t end = std::min(block.data.size(), segment_offset + s.bytes);
        const auto bytes = block.data.subspan(std::min(segment_offset, end), end - std::min(segment_offset, end));
        segment_offset = end;
        passes_left_in_segment = s.passes;
        // D.6: with bypass, significance and refinement passes after the first four bit-planes
        // (pass index 10 on) are raw; the segmentation puts them in segments of their own.
        raw = style_.bypass && k >= 10 && type != PassType::Cleanup;
        if (raw)
          raw_.start(bytes);
        else
          mq_.start(bytes);
      }
      switch (type) {
        case PassType::Significance:
          significance_pass(plane, raw);
          break;
        case PassType::Refinement:
          refinement_pass(plane, raw);
          break;
        case PassType::Cleanup:
          cleanup_pass(plane);
          break;
      }
      --passes_left_in_segment;
      if (style_.reset) reset(cx_);  // D.4: contexts reset at the end of each pass
    }
  }

 private:
  std::uint8_t& flag(int x, int y) {
    return flags_[static_cast<std::size_t>(y + 1) * static_cast<std::size_t>(stride_) +
                  static_cast<std::size_t>(x + 1)];
  }
  std::int32_t& value(int x, int y) {
    return out_[static_cast<std::size_t>(y) * static_cast<std::size_t>(w_) + static_cast<std::size_t>(x)];
  }

  // D.7: in vertically causal mode the last row of a stripe ignores the stripe below.
  bool below_hidden(int y) const { return style_.vertically_causal && (y & 3) == 3; }

  bool sig(int x, int y) { return (flag(x, y) & kSignificant) != 0; }

  struct Neighbours {
    int h, v, d;
  };
  Neighbours count(int x, int y) {
    const bool hide = below_hidden(y);
    Neighbours n;
    n.h = sig(x - 1, y) + sig(x + 1, y);
    n.v = sig(x, y - 1) + (hide ? 0 : sig(x, y + 1));
    n.d = sig(x - 1, y - 1) + sig(x + 1, y - 1) + (hide ? 0 : sig(x - 1, y + 1) + sig(x + 1, y + 1));
    return n;
  }
  int zero_context(int x, int y) {
    const Neighbours n = count(x, y);
    switch (orientation_) {
      case BandOrientation::HL:
        return zero_context_lh(n.v, n.h, n.d);
      case BandOrientation::HH:
        return zero_context_hh(n.h, n.v, n.d);
      default:
        return zero_context_lh(n.h, n.v, n.d);
    }
  }
  // +1, -1 or 0 for a neighbour's contribution to the sign context (Table D.2).
  int contribution(int x, int y) {
    const std::uint8_t f = flag(x, y);
    if (!(f & kSignificant)) return 0;
    return (f & kNegative) ? -1 : 1;
  }
  int decode_sign(int x, int y) {
    const bool hide = below_hidden(y);
    const int h = std::clamp(contribution(x - 1, y) + contribution(x + 1, y), -1, 1);
    const int v = std::clamp(contribution(x, y - 1) + (hide ? 0 : contribution(x, y + 1)), -1, 1);
    // Table D.3: {context, XORbit} by H = 1, 0, -1 (rows) and V = 1, 0, -1 (columns).
    static constexpr int kTable[3][3][2] = {
        {{13, 0}, {12, 0}, {11, 0}}, {{10, 0}, {9, 0}, {10, 1}}, {{11, 1}, {12, 1}, {13, 1}}};
    const auto& e = kTable[1 - h][1 - v];
    return mq_.decode(cx_[static_cast<std::size_t>(e[0])]) ^ e[1];
  }
  void become_significant(int x, int y, int negative, int plane) {
    flag(x, y) |= static_cast<std::uint8_t>(kSignificant | (negative ? kNegative : 0));
    const std::int32_t magnitude = std::int32_t{3} << plane;  // 1.5 * 2^plane, doubled
    value(x, y) = negative ? -magnitude : magnitude;
  }

  // D.3.1
  void significance_pass(int plane, bool raw) {
    for (int y0 = 0; y0 < h_; y0 += 4)
      for (int x = 0; x < w_; ++x)
        for (int y = y0; y < std::min(y0 + 4, h_); ++y) {
          std::uint8_t& f = flag(x, y);
          if (f & kSignificant) continue;
          const int context = zero_context(x, y);
          if (context == 0) continue;
          f |= kVisited;
          const int bit = raw ? raw_.bit() : mq_.decode(cx_[static_cast<std::size_t>(context)]);
          if (bit) become_significant(x, y, raw ? raw_.bit() : decode_sign(x, y), plane);
        }
  }

  // D.3.3
  void refinement_pass(int plane, bool raw) {
    const std::int32_t half = std::int32_t{1} << plane;
    for (int y0 = 0; y0 < h_; y0 += 4)
      for (int x = 0; x < w_; ++x)
        for (int y = y0; y < std::min(y0 + 4, h_); ++y) {
          std::uint8_t& f = flag(x, y);
          if ((f & (kSignificant | kVisited)) != kSignificant) continue;
          int bit;
          if (raw) {
            bit = raw_.bit();
          } else {
            int context = 16;
            if (!(f & kRefined)) {
              const Neighbours n = count(x, y);
              context = (n.h + n.v + n.d) ? 15 : 14;
            }
            bit = mq_.decode(cx_[static_cast<std::size_t>(context)]);
          }
          f |= kRefined;
          // The interval halves: its middle moves up or down by a quarter of the old width.
          std::int32_t& v = value(x, y);
          const std::int32_t step = bit ? half : -half;
          v += v < 0 ? -step : step;
        }
  }

  // D.3.4, with the segmentation symbol of D.5.
  void cleanup_pass(int plane) {
    for (int y0 = 0; y0 < h_; y0 += 4)
      for (int x = 0; x < w_; ++x) {
        int y = y0;
        const int y_end = std::min(y0 + 4, h_);
        if (y_end - y0 == 4 && run_length_applies(x, y0)) {
          if (!mq_.decode(cx_[kRunLength])) continue;  // four insignificant samples
          int r = mq_.decode(cx_[kUniform]) << 1;
          r |= mq_.decode(cx_[kUniform]);
          y = y0 + r;
          become_significant(x, y, decode_sign(x, y), plane);
          ++y;
        }
        for (; y < y_end; ++y) {
          std::uint8_t& f = flag(x, y);
          if (f & (kSignificant | kVisited)) continue;
          if (mq_.decode(cx_[static_cast<std::size_t>(zero_context(x, y))]))
            become_significant(x, y, decode_sign(x, y), plane);
        }
      }
    for (std::uint8_t& f : flags_) f &= static_cast<std::uint8_t>(~kVisited);
    if (style_.segmentation_symbols) {
      // 1010 in the UNIFORM context; a mismatch marks a corrupt pass, but the data decoded so far
      // stands (the decoder has no better value to put in its place).
      for (int i = 0; i < 4; ++i) mq_.decode(cx_[kUniform]);
    }
  }

  bool run_length_applies(int x, int y0) {
    for (int y = y0; y < y0 + 4; ++y) {
      if (flag(x, y) & (kSignificant | kVisited)) return false;
      const Neighbours n = count(x, y);
      if (n.h + n.v + n.d) return false;
    }
    return true;
  }

  int w_, h_, stride_;
  BandOrientation orientation_;
  t1::BlockStyle style_;
  std::span<std::int32_t> out_;
  std::vector<std::uint8_t> flags_;
  Contexts cx_{};
  MqDecoder mq_;
  RawDecoder raw_;
};

inline void decode_code_block(const BlockCodewords& block, int width, int height, BandOrientation orientation,
                              const t1::BlockStyle& style, std::span<std::int32_t> out) {
  std::fill(out.begin(), out.end(), 0);
  if (block.passes <= 0 || width <= 0 || height <= 0) return;
  if (block.top_plane > kMaxTopPlane)
    throw std::runtime_error("a code-block has " + std::to_string(block.top_plane + 1) +
                             " magnitude bit-planes; this decoder handles at most " + std::to_string(kMaxTopPlane + 1));
  BlockDecoder decoder(width, height, orientation, style, out);
  decoder.run(block);
}

}  // namespace t1dec_ref
