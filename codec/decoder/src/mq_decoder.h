#pragma once
#include <bit>
#include <cstddef>
#include <cstdint>
#include <span>

#include "codec/t1/mq_states.h"

namespace codec::dec {

// An adaptive probability context packed as (state index << 1) | MPS, the index of its row in
// t1::kMqTransitions: one lookup gives Qe and the packed context after an MPS or an LPS (with
// the MPS swap of Table C.2 folded in).
using MqDecoderContext = std::uint8_t;
inline constexpr MqDecoderContext mq_context(int state, int mps) {
  return static_cast<MqDecoderContext>(state << 1 | mps);
}

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
    const t1::MqTransition& t = t1::kMqTransitions[cx];
    const std::uint32_t qe = t.qe;
    const std::uint32_t qe_high = qe << 16;  // Qe against C's upper half, without shifting C
    const int mps = cx & 1;
    a_ -= qe;
    if (c_ < qe_high) {
      int d;
      if (a_ < qe) {
        d = mps;
        cx = t.next[1];
      } else {
        d = 1 - mps;
        cx = t.next[0];
      }
      a_ = qe;
      renormalise();
      return d;
    }
    c_ -= qe_high;
    if (a_ & 0x8000) return mps;  // the common case: an MPS with no renormalisation
    int d;
    if (a_ < qe) {
      d = 1 - mps;
      cx = t.next[0];
    } else {
      d = mps;
      cx = t.next[1];
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
