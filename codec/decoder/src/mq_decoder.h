#pragma once
#include <array>
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
    // INITDEC (Figure C.20), with C 32 bits further up and more bytes read ahead (below).
    data_ = segment.data();
    size_ = segment.size();
    pos_ = 0;
    c_ = std::uint64_t{byte_at(0)} << 48;
    ct_ = 0;
    refill();
    c_ <<= 7;
    ct_ -= 7;
    a_ = 0x8000;
  }

  // DECODE (Figure C.15) with LPS_EXCHANGE (C.17) and MPS_EXCHANGE (C.16), without a branch on
  // which sub-interval C falls in: that one is as unpredictable as the decisions themselves. This
  // form keeps one branch, for the MPS that needs no renormalisation: the better choice where
  // decisions are that skewed (the cleanup's run-length decisions, nearly all "four quiet samples").
  int decode(MqDecoderContext& cx) {
    const Step s = step(cx);
    if (a_ & 0x8000) return static_cast<int>(s.mps);
    cx = successor(cx, s);
    renormalise(renormalisation_shift());
    return static_cast<int>(s.mps ^ s.exchanged);
  }

  // The same without that branch (a renormalisation by 0 bits where none is due, and the context
  // rewritten as it was): the better choice for every other decision. Measured on the 2048x2048
  // mosaic, 1 thread: with the significance and refinement passes on this form, a lossless decode
  // took 10 % and a 0.75 bpp one 6 % less time than with the decoder that branched on the
  // sub-interval (2026-11-26). Once step() had no hidden branch left (2026-11-28), the cleanup's
  // zero-coding decisions and the signs gained from this form too (lossless, user time: 0.56 s
  // against 0.58 s with them on decode()).
  int decode_even(MqDecoderContext& cx) {
    const MqDecoderContext packed = cx;
    const Step s = step(cx);
    const int shift = renormalisation_shift();
    const MqDecoderContext next = successor(packed, s);
    cx = shift != 0 ? next : packed;
    renormalise(shift);
    return static_cast<int>(s.mps ^ s.exchanged);
  }

 private:
  struct Step {
    unsigned mps;        // the context's MPS
    unsigned exchanged;  // 1: the decision is the LPS
  };
  // Splits the interval by the context's Qe and keeps the sub-interval C is in; A may then be below
  // 0x8000 (always in the lower one: A = Qe < 0x8000).
  Step step(MqDecoderContext packed) {
    const std::uint32_t qe = packed >> 16;
    const std::uint64_t qe_high = std::uint64_t{qe} << 48;  // Qe against C's top 16 bits
    const std::uint32_t a = a_ - qe;
    const bool lower = c_ < qe_high;  // C in the LPS sub-interval
    const bool smaller = a < qe;      // the MPS sub-interval is the smaller one (conditional exchange)
    // A mask, not a select: GCC 12 compiled `c_ = lower ? c_ : c_ - qe_high` to a branch, as
    // unpredictable as the decisions (taken for about 60 % of the significance pass's). The mask
    // costs instructions (a lossless 1024x1024 decode: 876 M to 932 M) but a lossless 2048x2048
    // one took 10-13 % less user time, 1 thread, on an AMD EPYC (2026-11-28).
    c_ -= qe_high & (std::uint64_t{lower} - 1);
    a_ = lower ? qe : a;
    return Step{packed & 1u, static_cast<unsigned>(lower) ^ static_cast<unsigned>(smaller)};
  }

  // The context's state after a decision that renormalises: kMqDecoderNext's [0] after an LPS, [1]
  // after an MPS.
  static MqDecoderContext successor(MqDecoderContext packed, Step s) {
    return kMqDecoderNext[packed & 0xFFu][s.exchanged ^ 1u];
  }

  // The shift that brings A back to at least 0x8000 (0 if it is): A is never 0 (every Qe is
  // nonzero), so the builtin needs no test for 0, where std::countl_zero has one on a machine
  // without LZCNT (the baseline x86-64 this builds for): about 1 % of a lossless decode's instructions.
  int renormalisation_shift() const { return __builtin_clz(a_) - 16; }

  std::uint8_t byte_at(std::size_t i) const { return i < size_ ? data_[i] : 0xFF; }

  // C is the standard's 32-bit register shifted up by 32 (its top 16 bits, those compared with Qe,
  // are bits 48-63), so that whole bytes can be read ahead below it: CT counts the bits there, up
  // to 40. BYTEIN (Figure C.19) puts a byte just below the CT bits already there (where the
  // standard's register would get it once CT ran out), or 7 bits of one after a 0xFF (stuffed);
  // a 0xFF followed by a byte above 0x8F is a marker (or the end) and is never consumed: 1-bits
  // are fed instead. Sums and shifts commute, so this is the standard's C, read earlier, and a
  // byte is read once every few symbols instead of a test for it at each renormalisation.
  void refill() {
    while (ct_ <= 32) {
      if (byte_at(pos_) == 0xFF) {
        if (byte_at(pos_ + 1) > 0x8F) {
          c_ += std::uint64_t{0xFF} << (40 - ct_);
          ct_ += 8;
        } else {
          ++pos_;
          c_ += std::uint64_t{byte_at(pos_)} << (41 - ct_);
          ct_ += 7;
        }
      } else {
        ++pos_;
        c_ += std::uint64_t{byte_at(pos_)} << (40 - ct_);
        ct_ += 8;
      }
    }
  }

  // RENORMD (Figure C.18) shifts until A >= 0x8000; the shift count is known up front (A is nonzero:
  // every Qe is), at most 15, and CT covers it after a refill.
  void renormalise(int shift) {
    if (ct_ < shift) refill();
    a_ <<= shift;
    c_ <<= shift;
    ct_ -= shift;
  }

  const std::uint8_t* data_ = nullptr;
  std::size_t size_ = 0;
  std::size_t pos_ = 0;
  std::uint32_t a_ = 0;
  std::uint64_t c_ = 0;
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
