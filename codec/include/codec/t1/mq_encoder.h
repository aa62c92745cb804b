#pragma once
#include <bit>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "codec/t1/mq_states.h"

namespace codec::t1 {

// One adaptive probability estimate: a row of T.800 Table C.2 and the current MPS sense.
// Stored as a 16-bit word rather than a byte so that the encoder's register updates are not
// treated as possibly aliased by context writes (a char-typed store may alias anything).
struct MqContext {
  std::uint16_t packed = 0;  // (state index << 1) | MPS

  constexpr MqContext() = default;
  constexpr MqContext(int state, int mps) : packed(static_cast<std::uint16_t>((state << 1) | mps)) {}
  constexpr int state() const { return packed >> 1; }
  constexpr int mps() const { return packed & 1; }
};

// Where a not-yet-terminated MQ codeword could be cut. `committed` counts the bytes already in
// the output (including the last one, which a carry may still change); `buffered_bits` counts
// the code bits still held in the C register that the decoder needs to resolve every symbol
// coded so far. Resolve it into a byte count with safe_truncation_length() once the segment ends.
struct MqTruncationPoint {
  std::size_t committed = 0;
  int buffered_bits = 0;
  std::size_t segment_start = 0;
};

// The MQ arithmetic encoder of T.800 Annex C (C.2), writing one codeword segment at a time onto
// the end of a byte vector. Segments are independent codewords (INITENC ... FLUSH); contexts
// live outside the coder so that they can survive a termination, as JPEG 2000's mode switches
// require.
class MqEncoder {
 public:
  using Context = MqContext;

  explicit MqEncoder(std::vector<std::uint8_t>& out) : out_(&out) {}

  // INITENC (C.2.8): starts a new codeword segment at the current end of the output.
  void start();

  // ENCODE (C.2.2) with CODEMPS/CODELPS (C.2.5, C.2.6) and their conditional exchange.
  void encode(int bit, Context& cx) {
    const MqTransition& t = kMqTransitions[cx.packed];
    const std::uint32_t qe = t.qe;
    a_ -= qe;
    coded_ = true;
    if (bit == cx.mps()) {
      if (a_ & 0x8000) {  // MPS without renormalisation: by far the most frequent path
        c_ += qe;
        return;
      }
      if (a_ < qe)
        a_ = qe;  // conditional exchange: the MPS takes the (larger) lower sub-interval
      else
        c_ += qe;
      cx.packed = t.after_mps;
    } else {
      if (a_ < qe)
        c_ += qe;  // conditional exchange: the LPS takes the upper sub-interval
      else
        a_ = qe;
      cx.packed = t.after_lps;
    }
    renormalize();
  }

  // FLUSH (C.2.9): the shortest standard termination; a trailing 0xFF is dropped because the
  // decoder reads 0xFF past the end anyway. A segment that coded nothing stays empty.
  void flush();

  // Predictable termination (D.4.2, "ERTERM"): emits exactly the register bits down to the most
  // significant bit of the interval width, no bit chosen freely, so a decoder can check the tail.
  void flush_predictable();

  MqTruncationPoint truncation_point() const { return {out_->size(), 27 - ct_, segment_start_}; }
  std::size_t segment_start() const { return segment_start_; }

 private:
  // RENORME (C.2.7), shifting in one go up to the next byte boundary instead of bit by bit.
  void renormalize() {
    int shift = std::countl_zero(a_) - 16;  // a_ is in [1, 0x8000) here: shifts until bit 15 is set
    while (shift >= ct_) {
      a_ <<= ct_;
      c_ <<= ct_;
      shift -= ct_;
      byte_out();  // sets ct_ to 8 or 7
    }
    a_ <<= shift;
    c_ <<= shift;
    ct_ -= shift;
  }

  // BYTEOUT (C.2.7) with carry propagation and bit stuffing after 0xFF. Inline on purpose: with
  // no out-of-line call on the coding path, a coder copied into a local variable (as the coding
  // passes do) lives entirely in CPU registers instead of being reloaded for every symbol.
  void byte_out() {
    std::vector<std::uint8_t>& out = *out_;
    const bool has_last = has_last_byte();
    if (has_last && out.back() == 0xFF) {
      // Bit stuffing: the byte after 0xFF carries 7 bits, its MSB left free to absorb a carry.
      emit_stuffed();
      return;
    }
    if (c_ & 0x8000000) {
      // Carry into the byte already written. The first byte of a segment never receives one: the
      // 12 initial shifts leave the whole initial interval below bit 27.
      ++out.back();
      c_ &= 0x7FFFFFF;
      if (out.back() == 0xFF) {
        emit_stuffed();
        return;
      }
    }
    out.push_back(static_cast<std::uint8_t>(c_ >> 19));
    c_ &= 0x7FFFF;
    ct_ = 8;
  }

  void emit_stuffed() {
    out_->push_back(static_cast<std::uint8_t>(c_ >> 20));
    c_ &= 0xFFFFF;
    ct_ = 7;
  }

  bool has_last_byte() const { return out_->size() > segment_start_; }

  std::vector<std::uint8_t>* out_;
  std::size_t segment_start_ = 0;
  std::uint32_t a_ = 0x8000;
  std::uint32_t c_ = 0;
  int ct_ = 12;
  bool coded_ = false;
};

// The number of bytes of `data` a decoder needs (reading 0xFF past the end, as T.800 C.3.4 and
// every practical decoder do) to decode every symbol coded before `point` was taken, once the
// segment that began at point.segment_start has been written up to `segment_end`.
//
// Why this is safe: decoding the first n symbols right only needs the code value to lie in the
// encoder's interval [C, C + A) at that time. If the kept bytes hold every bit of the C register
// down to its least significant one, the value they and the 0xFF fill spell lies in that interval
// whatever follows. The register held `buffered_bits` such bits; later bytes carry 8 of them, or 7
// after a 0xFF (the stuffed bit), and the final bytes tell which.
std::size_t safe_truncation_length(std::span<const std::uint8_t> data, const MqTruncationPoint& point,
                                   std::size_t segment_end);

}  // namespace codec::t1
