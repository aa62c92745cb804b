#pragma once
#include <array>
#include <cstddef>
#include <cstdint>

// The last stage of a tile's decode, one row at a time: the inverse component transform of
// components 0..2 (T.800 G.2: RCT on reversible planes, ICT on 9/7 ones), the DC level shift back to
// unsigned, the rounding of 9/7 samples to integers and the clamping to each component's range
// (G.1.2), straight from the inverse DWT's planes into the output samples. One pass instead of a
// transform in place and a store after it; the rows are vectorised with Highway (dispatched at run
// time) and equal the scalar reference rows below bit for bit.
namespace codec::dec {

// What a component's samples become after the inverse DWT and transform (G.1.2): v + shift,
// clamped to [lo, hi].
struct SampleRange {
  std::int32_t shift = 0;  // 2^(precision-1) for unsigned components, 0 for signed ones
  std::int32_t lo = 0, hi = 0;
};
SampleRange sample_range(int precision, bool is_signed);  // precision 1..31

// The three output rows of components 0..2 after a component transform; a null row is a
// component decoded for the transform but not output.
using OutputRows = std::array<std::int32_t*, 3>;
using OutputRanges = std::array<SampleRange, 3>;

// n samples of one plane without a component transform.
void ints_to_samples(const std::int32_t* in, const SampleRange& range, std::int32_t* out, std::size_t n);
void floats_to_samples(const float* in, const SampleRange& range, std::int32_t* out, std::size_t n);
// n samples of components 0..2 through the inverse RCT (G-7) or ICT (G-9).
void rct_to_samples(const std::int32_t* y, const std::int32_t* cb, const std::int32_t* cr, const OutputRanges& ranges,
                    const OutputRows& out, std::size_t n);
void ict_to_samples(const float* y, const float* cb, const float* cr, const OutputRanges& ranges, const OutputRows& out,
                    std::size_t n);

// Components of more than 31 bits (up to T.800's 38), and any from 64-bit planes: G.1.2 one
// sample at a time in int64, and the inverse RCT and ICT in int64 and double (G-7, G-9).
struct WideSampleRange {
  std::int64_t shift = 0;
  std::int64_t lo = 0, hi = 0;
};
WideSampleRange wide_sample_range(int precision, bool is_signed);  // precision 1..38
// v + shift clamped to [lo, hi]; a double rounded to the nearest integer first (ties to even), 0
// if it is not a finite number.
std::int64_t wide_sample(std::int64_t v, const WideSampleRange& range);
std::int64_t wide_sample(double v, const WideSampleRange& range);
// Component c (0 R, 1 G, 2 B) of the inverse RCT or ICT of one sample's Y, Cb, Cr.
std::int64_t inverse_rct(std::int64_t y, std::int64_t cb, std::int64_t cr, std::size_t c);
double inverse_ict(double y, double cb, double cr, std::size_t c);

// The scalar rows, one sample at a time as the decoder stored them before the vectorised pass:
// the definition the rows above must meet (sample_output_test), and what they fall back to where
// a range does not fit the vector lanes' float arithmetic exactly.
namespace reference {
void ints_to_samples(const std::int32_t* in, const SampleRange& range, std::int32_t* out, std::size_t n);
void floats_to_samples(const float* in, const SampleRange& range, std::int32_t* out, std::size_t n);
void rct_to_samples(const std::int32_t* y, const std::int32_t* cb, const std::int32_t* cr, const OutputRanges& ranges,
                    const OutputRows& out, std::size_t n);
void ict_to_samples(const float* y, const float* cb, const float* cr, const OutputRanges& ranges, const OutputRows& out,
                    std::size_t n);
}  // namespace reference

}  // namespace codec::dec
