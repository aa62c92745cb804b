#pragma once
#include <array>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <span>

#include "codec/t1/mq_states.h"

namespace codec::dec {

// An adaptive probability context packed as (Qe << 16) | (state index << 1) | MPS: the common
// decision (an MPS without renormalisation) needs nothing but this word, and only a decision
// that renormalises looks up its successor (kMqDecoderNext, indexed by the low byte).
using MqDecoderContext = std::uint32_t;
inline constexpr MqDecoderContext mq_context(int state, int mps) {
  return static_cast<MqDecoderContext>(t1::kMqStates[static_cast<std::size_t>(state)].qe) << 16 |
         static_cast<MqDecoderContext>(state << 1 | mps);
}

// t1::kMqTransitions with its successors packed as above: [0] after an LPS, [1] after an MPS.
inline constexpr std::array<std::array<MqDecoderContext, 2>, 2 * t1::kMqStateCount> kMqDecoderNext = [] {
  std::array<std::array<MqDecoderContext, 2>, 2 * t1::kMqStateCount> t{};
  for (std::size_t i = 0; i < t.size(); ++i)
    for (std::size_t k = 0; k < 2; ++k) {
      const int next = t1::kMqTransitions[i].next[k];
      t[i][k] = mq_context(next >> 1, next & 1);
    }
  return t;
}();

// The MQ arithmetic decoder of T.800 C.3 (INITDEC, DECODE, RENORMD, BYTEIN; Figures C.15-C.20),
// over one codeword segment. Past the segment's end it reads 0xFF bytes: BYTEIN then sees a
// marker and feeds 1-bits, as C.3.4 prescribes, so a short or truncated segment decodes to
// something bounded instead of reading outside its bytes.
//
// Everything is inline and the state is a handful of scalars: tier-1 copies the decoder into a
// local for a whole coding pass and writes it back after, so that A, C, CT and the position live
// in registers instead of being stored and reloaded around every symbol.
class MqDecoder {
 public:
  void start(std::span<const std::uint8_t> segment) {
    // INITDEC (Figure C.20).
    data_ = segment.data();
    size_ = segment.size();
    pos_ = 0;
    c_ = static_cast<std::uint32_t>(byte_at(0)) << 16;
    byte_in();
    c_ <<= 7;
    ct_ -= 7;
    a_ = 0x8000;
  }

  int decode(MqDecoderContext& cx) {
    // DECODE (Figure C.15) with LPS_EXCHANGE (C.17) and MPS_EXCHANGE (C.16).
    const MqDecoderContext packed = cx;
    const std::uint32_t qe_high = packed & 0xFFFF0000u;  // Qe against C's upper half, without shifting C
    const std::uint32_t qe = packed >> 16;
    const int mps = static_cast<int>(packed & 1u);
    a_ -= qe;
    if (c_ < qe_high) {
      const auto& next = kMqDecoderNext[packed & 0xFFu];
      int d;
      if (a_ < qe) {
        d = mps;
        cx = next[1];
      } else {
        d = 1 - mps;
        cx = next[0];
      }
      a_ = qe;
      renormalise();
      return d;
    }
    c_ -= qe_high;
    if (a_ & 0x8000) return mps;  // the common case: an MPS with no renormalisation
    const auto& next = kMqDecoderNext[packed & 0xFFu];
    int d;
    if (a_ < qe) {
      d = 1 - mps;
      cx = next[0];
    } else {
      d = mps;
      cx = next[1];
    }
    renormalise();
    return d;
  }

 private:
  std::uint8_t byte_at(std::size_t i) const { return i < size_ ? data_[i] : 0xFF; }

  void byte_in() {
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

  void renormalise() {
    // RENORMD (Figure C.18) shifts until A >= 0x8000, reading a byte whenever CT runs out. The
    // shift count is known up front (A < 0x8000 here, and nonzero: every Qe is); when CT covers
    // it, one shift does the loop's work without a byte read in between.
    const int shift = std::countl_zero(a_) - 16;
    if (shift <= ct_) {
      a_ <<= shift;
      c_ <<= shift;
      ct_ -= shift;
      return;
    }
    do {
      if (ct_ == 0) byte_in();
      a_ <<= 1;
      c_ <<= 1;
      --ct_;
    } while ((a_ & 0x8000) == 0);
  }

  const std::uint8_t* data_ = nullptr;
  std::size_t size_ = 0;
  std::size_t pos_ = 0;
  std::uint32_t a_ = 0, c_ = 0;
  int ct_ = 0;
};

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

}  // namespace codec::dec
