#include "codec/t1/mq_encoder.h"

#include <algorithm>
#include <cassert>

namespace codec::t1 {

void MqEncoder::start() {
  segment_start_ = out_->size();
  a_ = 0x8000;
  c_ = 0;
  // 12, not 13: the byte before a new segment is never 0xFF here, because every segment this
  // coder ends drops a trailing 0xFF (and the raw writer never ends on one).
  ct_ = 12;
}

MqEncoder::AfterByteOut MqEncoder::byte_out(std::vector<std::uint8_t>& out, std::size_t segment_start,
                                            std::uint32_t c) {
  const bool has_last = out.size() > segment_start;
  if (has_last && out.back() == 0xFF) {
    // Bit stuffing: the byte after 0xFF carries 7 bits, its MSB left free to absorb a carry.
    out.push_back(static_cast<std::uint8_t>(c >> 20));
    return {c & 0xFFFFF, 7};
  }
  if (c & 0x8000000) {
    // Carry into the byte already written. The first byte of a segment never receives one: the
    // 12 initial shifts leave the whole initial interval below bit 27.
    assert(has_last);
    ++out.back();
    c &= 0x7FFFFFF;
    if (out.back() == 0xFF) {
      out.push_back(static_cast<std::uint8_t>(c >> 20));
      return {c & 0xFFFFF, 7};
    }
  }
  out.push_back(static_cast<std::uint8_t>(c >> 19));
  return {c & 0x7FFFF, 8};
}

void MqEncoder::flush() {
  if (untouched()) return;  // an empty segment needs no bytes: no symbol has to be decoded from it
  // SETBITS: the value in [C, C + A) with the most trailing ones, which the decoder's 0xFF fill
  // reproduces for free.
  const std::uint32_t top = c_ + a_;
  c_ |= 0xFFFF;
  if (c_ >= top) c_ -= 0x8000;
  c_ <<= ct_;
  byte_out();
  c_ <<= ct_;
  byte_out();
  if (has_last_byte() && out_->back() == 0xFF) out_->pop_back();
}

void MqEncoder::flush_predictable() {
  // Output the register bits down to bit 15 (the weight of A's leading one): the kept bits of C
  // followed by the decoder's one-fill then lie within [C, C + 2^15) which is inside [C, C + A).
  int bits_needed = 12 - ct_;
  while (bits_needed > 0) {
    c_ <<= ct_;
    ct_ = 0;
    byte_out();
    bits_needed -= ct_;  // the byte just written held ct_ (8, or 7 after 0xFF) register bits
  }
  if (has_last_byte() && out_->back() == 0xFF) out_->pop_back();
}

std::size_t safe_truncation_length(std::span<const std::uint8_t> data, const MqTruncationPoint& point,
                                   std::size_t segment_end) {
  segment_end = std::min(segment_end, data.size());
  std::size_t length = point.committed;
  int bits = point.buffered_bits;
  while (bits > 0 && length < segment_end) {
    const bool after_ff = length > point.segment_start && data[length - 1] == 0xFF;
    bits -= after_ff ? 7 : 8;
    ++length;
  }
  return std::min(length, segment_end);
}

// Derivation. Number the segment's bytes from S = point.segment_start; byte j carries k_j bits,
// 7 when byte j - 1 (j > S) is 0xFF and 8 otherwise, and a 7-bit byte's MSB overlaps the 0xFF's
// LSB (the stuffed bit, where a carry into the 0xFF lands). Let P_L be the value of bytes S..L-1
// and ulp_L the weight of byte L-1's LSB (ulp_S = 1, the initial interval [0, 1)). A decoder cut
// after L bytes reads 1 bits from there on (BYTEIN's fill: 0xFF, then "marker" 0xFF 0xFF...), so
// its code value is V_L = P_L + ulp_L - e, e smaller than any weight the coder ever uses. Each
// decision picks the sub-interval that holds the code value, so the first n decisions come out
// right exactly when V_L lies in the encoder's interval [Low, Hi) after them: when
//     Low < P_L + ulp_L <= Hi.                                                          (*)
// At the point: Low = Q + C u, Hi = Q + (C + A) u, with Q the value of the E = committed bytes as
// they were then (the last, last_byte, may still take a carry) and u = ulp_E 2^-(27 - CT).
//
// Cuts at L >= E read the final bytes: (*) is checked in exact integer arithmetic relative to
// P_{E-1}, in units of u 2^-24 (everything then fits in 64 bits), scanning L upwards. The cut
// that keeps every bit of C (safe_truncation_length) satisfies (*), so the scan ends there.
//
// Cuts at L < E read only bytes that no carry will change any more. Write Y_L = P_L + ulp_L - Q,
// so (*) reads C u < Y_L <= (C + A) u, and Y_E = ulp_E, Y_L = c_L ulp_{L+1} + Y_{L+1} with
// c_L = 2^k_L - 1 - b_L (b the bytes as they were at the point). Then
//  - c_L = 0 (byte L all ones: 0xFF, or 0x7F after a 0xFF): Y_L = Y_{L+1}, (*) at L is (*) at L+1;
//  - c_L >= 1: when BYTEOUT wrote byte L it kept below it C' < ulp_{L+1} and A < 2^16 <= ulp_{L+1}/8
//    (in register units), and the interval only shrinks, so (C + A) u < 1.125 ulp_{L+1} - T with
//    T = Q - P_{L+1} >= 0 (carries into byte L only raise P_{L+1}), while Y_L >= 2 ulp_{L+1} - T:
//    (*) fails;
//  - c_L <= -1 (a stuffed byte that carried into the 0xFF before it): Y_L <= Y_{L+1} - ulp_{L+1}
//    = -T <= 0 <= C u: (*) fails.
// So a cut before E works exactly when the bytes from the cut to E - 1 are all ones and
// C < 2^(27 - CT) <= C + A (which is (*) for Y_E = ulp_E), and then the earliest such cut is
// the answer. Both parts are exact, and (*) at n symbols implies (*) before, so minimal lengths
// never decrease from one point to the next. A minimal cut never ends on a 0xFF (P_L + ulp_L
// is then the same as for L - 1).
std::size_t minimal_truncation_length(std::span<const std::uint8_t> data, const MqTruncationPoint& point,
                                      std::size_t segment_end, std::size_t lower_bound) {
  segment_end = std::min(segment_end, data.size());
  const std::size_t start = point.segment_start;
  const std::size_t committed = point.committed;
  const std::size_t lower = std::max(lower_bound, start);
  if (lower >= segment_end || committed > segment_end || point.ct < 1 || point.ct > 12) return segment_end;
  auto all_ones = [&](std::size_t j, unsigned byte) {
    return byte == (j > start && data[j - 1] == 0xFF ? 0x7Fu : 0xFFu);
  };

  const int below = 27 - point.ct;  // register bits below the last committed byte's LSB
  const std::uint64_t c = point.c;
  const std::uint64_t a = point.a;
  if (committed > start && lower < committed && c < (std::uint64_t{1} << below) &&
      (std::uint64_t{1} << below) <= c + a && all_ones(committed - 1, point.last_byte)) {
    std::size_t length = committed - 1;
    while (length > lower && all_ones(length - 1, data[length - 1])) --length;
    return length;
  }

  constexpr int kGuard = 24;  // fraction bits below the register's LSB: room for 3 more bytes
  std::uint64_t weight = std::uint64_t{1} << (below + kGuard);  // ulp_L, now L = committed
  std::uint64_t value = 0;                                      // P_L - P_{committed - 1}
  std::uint64_t low = c << kGuard;
  if (committed > start) {
    value = std::uint64_t{data[committed - 1]} * weight;
    low += std::uint64_t{point.last_byte} * weight;
  }
  const std::uint64_t high = low + (a << kGuard);
  for (std::size_t length = committed;; ++length) {
    if (length >= segment_end) return segment_end;  // the whole terminated segment decodes
    if (length >= lower && low < value + weight && value + weight <= high) return length;
    const int bits = length > start && data[length - 1] == 0xFF ? 7 : 8;
    if (weight >> bits == 0) break;  // past every bit of C: cannot happen (see above)
    weight >>= bits;
    value += std::uint64_t{data[length]} * weight;
  }
  assert(false && "no truncation length found below the safe one");
  return std::clamp(safe_truncation_length(data, point, segment_end), lower, segment_end);
}

}  // namespace codec::t1
