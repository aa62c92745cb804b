#pragma once
#include <algorithm>
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

// Where a not-yet-terminated MQ codeword could be cut: the encoder's state once the last symbol
// before the cut has been coded. `committed` counts the bytes already in the output (including
// the last one, `last_byte`, which a carry may still change); `buffered_bits` counts the code bits
// still held in the C register that the decoder needs to resolve every symbol coded so far.
// `c`, `a` and `ct` are the C, A and CT registers: the encoder's interval is
// [C, C + A) in units of 2^-(27 - CT) of the last committed byte's least significant bit.
// Resolve it into a byte count with minimal_truncation_length() (or the cruder
// safe_truncation_length()) once the segment ends.
struct MqTruncationPoint {
  std::size_t committed = 0;
  int buffered_bits = 0;
  std::size_t segment_start = 0;
  std::uint32_t c = 0;
  std::uint32_t a = 0x8000;
  int ct = 12;
  std::uint8_t last_byte = 0;  // out[committed - 1] at the time, when committed > segment_start
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
  // Forced inline: it is the block coder's innermost operation (see also byte_out).
  [[gnu::always_inline]] void encode(int bit, Context& cx) {
    const MqTransition& t = kMqTransitions[cx.packed];
    const std::uint32_t qe = t.qe;
    const bool is_mps = bit == cx.mps();
    a_ -= qe;
    // CODEMPS and CODELPS differ only in which sub-interval the symbol gets: the upper one
    // (C += Qe, A keeps A - Qe) or the lower one (A = Qe). The MPS normally takes the upper one,
    // the LPS the lower; the conditional exchange (A - Qe < Qe) swaps them. Selecting instead of
    // branching avoids a misprediction on every symbol of a near-even context (refinement bits).
    // (Masks rather than ?:, which the compiler turns back into a branch.)
    const std::uint32_t upper = 0u - static_cast<std::uint32_t>(is_mps != (a_ < qe));  // all ones or zero
    c_ += qe & upper;
    a_ = (a_ & upper) | (qe & ~upper);
    // Renormalise: shift A until bit 15 is set, none when it is (only an MPS can leave it so, and
    // then the context keeps its state). Written without a branch on whether to renormalise, which
    // mispredicts on about every LPS and every renormalising MPS; the only branch left is the
    // rarer one for a byte to output.
    const int shift = std::countl_zero(a_) - 16;  // A is below 2^16 and not 0
    const std::uint32_t renormalising = 0u - static_cast<std::uint32_t>(shift != 0);
    cx.packed = static_cast<std::uint16_t>((t.next[is_mps] & renormalising) | (cx.packed & ~renormalising));
    if (shift >= ct_) [[unlikely]] {
      renormalize(shift);
      return;
    }
    a_ <<= shift;
    c_ <<= shift;
    ct_ -= shift;
  }

  // `count` zeros in context cx: the same as as many encode(0, cx), but the stretches where 0 is
  // the MPS and A stays at or above 0x8000 (no renormalisation, no exchange: each symbol only adds
  // Qe to C and takes it from A) are coded in one step. The run-length symbols of the empty stripe
  // columns that fill most blocks' top bit-planes come this way.
  void encode_zeros(Context& cx, int count) {
    while (count > 0) {
      if (cx.mps() == 0 && count > 2) {
        const std::uint32_t qe = kMqTransitions[cx.packed].qe;
        const std::uint32_t quiet = std::min((a_ - 0x8000) / qe, static_cast<std::uint32_t>(count));
        a_ -= quiet * qe;
        c_ += quiet * qe;  // C + A is unchanged, so C cannot outgrow its register
        count -= static_cast<int>(quiet);
        if (count == 0) return;
      }
      encode(0, cx);  // the symbol that renormalises (or an LPS)
      --count;
    }
  }

  // FLUSH (C.2.9): the shortest standard termination. A trailing 0xFF is dropped: the decoder's
  // 1-bit fill past the end stands in for it, and a codeword must not end on 0xFF anyway (it could
  // form a marker with what follows). A segment that coded nothing stays empty.
  void flush();

  // Predictable termination (D.4.2, "ERTERM"): emits exactly the register bits down to the most
  // significant bit of the interval width, no bit chosen freely, so a decoder can check the tail.
  void flush_predictable();

  // C holds 27 - CT code bits not yet output: BYTEOUT leaves bits 0..18 with CT = 8 (0..19 with
  // CT = 7 after a stuffed byte) and every shift adds one.
  MqTruncationPoint truncation_point() const {
    const std::uint8_t last = has_last_byte() ? out_->back() : std::uint8_t{0};
    return {out_->size(), 27 - ct_, segment_start_, c_, a_, ct_, last};
  }

 private:
  // RENORME (C.2.7), shifting in one go up to the next byte boundary instead of bit by bit.
  // `shift`: the shifts that set bit 15 of A, at least CT of them.
  [[gnu::always_inline]] void renormalize(int shift) {
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

  // BYTEOUT (C.2.7) with carry propagation and bit stuffing after 0xFF. The register C goes in
  // by value and comes back with the new CT: the coder's own address never reaches a function
  // the compiler cannot see into, so a coder copied into a local (as the coding passes do) can
  // live in CPU registers for a whole pass.
  struct AfterByteOut {
    std::uint32_t c;
    int ct;
  };
  static AfterByteOut byte_out(std::vector<std::uint8_t>& out, std::size_t segment_start, std::uint32_t c);
  void byte_out() {
    const AfterByteOut r = byte_out(*out_, segment_start_, c_);
    c_ = r.c;
    ct_ = r.ct;
  }

  bool has_last_byte() const { return out_->size() > segment_start_; }

  // Whether no symbol has been coded since start(): every symbol either adds Qe to C or
  // renormalises (which lowers CT, and never brings it back to 12).
  bool untouched() const { return c_ == 0 && ct_ == 12; }

  std::vector<std::uint8_t>* out_;
  std::size_t segment_start_ = 0;
  std::uint32_t a_ = 0x8000;
  std::uint32_t c_ = 0;
  int ct_ = 12;
};

// The number of bytes of `data` a decoder needs to decode every symbol coded before `point` was
// taken, once the segment that began at point.segment_start has been written up to `segment_end`.
// Past the bytes it is given the decoder is assumed to read 1 bits, which is what T.800's BYTEIN
// (C.3.4) produces once it meets 0xFF followed by a byte above 0x8F, i.e. the next marker or the
// 0xFF 0xFF that decoders conventionally append to a codeword.
//
// Why this is safe: decoding the first n symbols right only needs the code value to lie in the
// encoder's interval [C, C + A) at that time. If the kept bytes hold every bit of the C register
// down to its least significant one, the value they and the 0xFF fill spell lies in that interval
// whatever follows. The register held `buffered_bits` such bits; later bytes carry 8 of them, or 7
// after a 0xFF (the stuffed bit), and the final bytes tell which.
std::size_t safe_truncation_length(std::span<const std::uint8_t> data, const MqTruncationPoint& point,
                                   std::size_t segment_end);

// The smallest L >= max(lower_bound, point.segment_start) such that a T.800 decoder given only
// data[point.segment_start, L) of the finished segment (ending at `segment_end`), followed by the
// 0xFF fill of BYTEIN, decodes every symbol coded before `point` was taken exactly; never more
// than segment_end. Usually one to three bytes below safe_truncation_length(): the bits of C
// below the interval's resolution need not be sent when the decoder's 1-fill lands in
// [C, C + A) anyway, and a run of all-ones bytes before the cut is synthesised by the fill too.
// Exact (see the derivation in mq_encoder.cpp) and cheap: a few comparisons per point, plus a
// backward scan over a run of 0xFF / stuffed 0x7F bytes where there is one.
std::size_t minimal_truncation_length(std::span<const std::uint8_t> data, const MqTruncationPoint& point,
                                      std::size_t segment_end, std::size_t lower_bound);

}  // namespace codec::t1
