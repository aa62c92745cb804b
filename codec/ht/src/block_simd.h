#pragma once
#include <cstddef>
#include <cstdint>

// The HT block coder's loops over samples, vectorised with Highway and dispatched at run time.
namespace codec::ht::simd {

// A row of float coefficients quantised as t1::quantize(c, inverse_step, fraction) does, bit for
// bit: magnitude = the index's magnitude, negative = 1 where the index is negative, fraction =
// floor(256 * what the index drops), clamped to 0..255; and the magnitudes' bit lengths as
// bit_lengths gives them. Returns the OR of the magnitudes; `squares` receives the sum of the
// squared scaled magnitudes |c| * inverse_step (each at least its index plus fraction), in float.
std::uint32_t quantize_row(const float* row, std::size_t n, float inverse_step, std::uint32_t* magnitude,
                           std::uint8_t* negative, std::uint8_t* fraction, std::uint8_t* length,
                           std::uint8_t* length_below_top, float* squares);

// What a cleanup on plane p leaves, over all n samples, with v = magnitude + fraction / 256 (or
// the magnitude alone when `fraction` is null) and e_p(v) the residual after a cleanup on p
// (v itself below 2^p, else (magnitude mod 2^p) + fraction / 256 - half(p); half(p) = 2^(p-1),
// or `half_at_zero` at p = 0): energy = sum of v^2, after_cleanup = sum of e_p^2 and, with
// `refinement` (p >= 1), refined = the sum over samples at or above 2^p of e_p^2 - e_(p-1)^2 (the
// MagRef pass' decrease).
struct CleanupErrors {
  double energy = 0, after_cleanup = 0, refined = 0;
};
CleanupErrors cleanup_errors(const std::uint32_t* magnitude, const std::uint8_t* fraction, std::size_t n, int p,
                             double half_at_zero, bool refinement);

// The squared error a cleanup from each bit-plane leaves, for all planes at once (plane_statistics'
// costliest part: a sum over samples and their planes). For each plane p = 0 .. planes:
// error[p] = the sum over all samples of e_p^2, e_p = v = magnitude[i] + fraction[i] / 256 where
// magnitude[i] < 2^p, else (magnitude[i] mod 2^p) + fraction[i] / 256 - half(p), where half(p) =
// 2^(p-1) for p > 0 and `half_at_zero` for p = 0. `fraction` holds each sample's fraction below its
// index in 256ths (null: none, reversible). Magnitudes are below 2^31, planes at most 31.
// error[planes] (the energy) is exact; the others, estimates, are within 1e-5 of it (float sums).
// Planes below `lowest_plane` are not computed (their entries are left meaningless).
void plane_errors(const std::uint32_t* magnitude, const std::uint8_t* fraction, std::size_t n, int planes,
                  double half_at_zero, int lowest_plane, double* error);

// Per magnitude (each below 2^31), its bit length and that of the magnitude without its top bit
// (HtBlock::lengths, lengths_below_top).
void bit_lengths(const std::uint32_t* magnitude, std::size_t n, std::uint8_t* length, std::uint8_t* length_below_top);

// plane_statistics' counts over the quads of a block's leftmost columns, as many as whole SIMD
// chunks of quads cover (a multiple of twice the lane count; 0 for a narrower block), which it
// returns; the caller counts the rest. `lengths` and `lengths_below_top` are HtBlock's (row by row,
// `width` apart). For each plane p < `planes` it adds: to quads[p] the quads whose largest bit length
// l exceeds p; to samples[p] the samples whose own length exceeds p; to top_sums[p] the sum of l
// over those samples; and to extras[p] the samples whose min(t, own length) exceeds p, t the bit
// length of the quad's largest magnitude without its top bit. A missing row below the last odd one
// counts as insignificant samples.
std::size_t quad_counts(const std::uint8_t* lengths, const std::uint8_t* lengths_below_top, std::size_t width,
                        std::size_t height, int planes, std::int64_t* quads, std::int64_t* samples,
                        std::int64_t* top_sums, std::int64_t* extras);

// For the refinement passes on plane p - 1 (p >= 1): per column of a stripe of `rows` (1..4) rows
// of `width` magnitudes (row r at stripe + r * stride), one byte: bit r set where row r's magnitude
// is significant at plane p (at or above 2^p), and bit 4 + r its bit p - 1 (0 for rows past `rows`).
// With `fraction` (the magnitudes' fractions in 256ths, laid out as they are; p <= 15), bit 4 + r
// of a sample below 2^p is instead whether magnitude * 256 + fraction reaches `threshold`: SigProp
// raising (ht_block_encoder.cpp).
void stripe_columns(const std::uint32_t* stripe, const std::uint8_t* fraction, std::size_t width, std::size_t stride,
                    int rows, int p, std::int32_t threshold, std::uint8_t* columns);

// The cleanup's choice of indices (ht_block_encoder.cpp; README, "Raising near-significant
// samples" and "Lowering quads' exponents"), in two steps on its exponent grid. First, a code per
// sample: its offset within its index mu = magnitude >> p, in 256ths of 2^p ((magnitude mod 2^p) *
// 256 + fraction) >> p, at most kLargestLoweringOffset) where mu is the smallest index of its
// exponent (mu >= 2, mu - 1 a power of two); kRaise where mu is 0 and magnitude * 256 + fraction
// reaches raise_threshold (0: never); else kNoAdjustment. p <= 23.
inline constexpr std::uint8_t kLargestLoweringOffset = 200, kRaise = 254, kNoAdjustment = 255;
void adjustment_codes(const std::uint32_t* magnitude, const std::uint8_t* fraction, std::size_t n, int p,
                      std::uint32_t raise_threshold, std::uint8_t* codes);
// Then per row of quads, on the exponent cells quad_row_analysis reads (and codes laid out alike):
// 1. Raising: in a quad with a significant sample, every sample coded kRaise gets exponent 1.
// 2. Lowering: a quad whose largest exponent E >= 2 exceeds kappa (as quad_row_analysis finds it,
//    from the cells above as they stand) and whose samples at E have offsets summing to less than
//    256 / kLowerDenominator per significant sample gets those samples' exponents lowered by one.
// The cells change in `upper` and `lower`; pattern[q] says which samples: bit k lowered, bit 4 + k
// raised, k the quad's sample (left column top and bottom, then the right column's). Reads as
// quad_row_analysis does, rewrites the cells it reads (changing only the row's quads') and writes
// up to kQuadRowOverwrite patterns past `quads`. Returns whether any sample changed.
inline constexpr std::uint16_t kLowerDenominator = 10;
bool adjust_quad_row(const std::uint8_t* above, std::uint8_t* upper, std::uint8_t* lower,
                     const std::uint8_t* upper_codes, const std::uint8_t* lower_codes, std::size_t quads,
                     bool initial_row, std::uint16_t* pattern);

// The bits of a stripe's column bytes (stripe_columns') as row masks, 64 columns a word: bit x % 64
// of masks[b * words + x / 64] is bit b of columns[x], for x < width (every other bit 0). `words`
// must be at least (width + 63) / 64, and `masks` must have 8 bytes to spare after its 8 * words
// words (a vector's mask may be stored in whole words).
void column_bit_masks(const std::uint8_t* columns, std::size_t width, std::size_t words, std::uint64_t* masks);

// The cleanup pass' analysis of one row of quads (T.814 7.3), from the magnitude exponents E_n of
// its two rows of samples (`upper`, `lower`: the exponent of column x at [x]) and of the row above
// (`above`; unused in the first row of quads), each readable from column -2 to 2 * quads + 1 (0
// outside the block) and further: up to kQuadRowOverread bytes past that. Per quad q, the quad
// at columns 2q and 2q + 1:
//   index[q] = context << 9 | rho << 5 | (u_q > 0) << 4 | at_top: its context c_q (7.3.5), its
//     significance pattern rho (bit n: sample n, in the standard's order 7.3.1), whether it has a
//     residual and, if so, which samples' exponents equal U_q (the EMB patterns may imply their
//     top bit), as VlcEncodingTable indexes its codewords;
//   exponents[q] = U_q | u_q << 8: the exponent bound and the residual U_q - kappa_q (7.3.7).
// Writes up to kQuadRowOverwrite entries past `quads` in each output.
inline constexpr std::size_t kQuadRowOverread = 512;
inline constexpr std::size_t kQuadRowOverwrite = 256;
void quad_row_analysis(const std::uint8_t* above, const std::uint8_t* upper, const std::uint8_t* lower,
                       std::size_t quads, bool initial_row, std::uint16_t* index, std::uint16_t* exponents);

// The MagSgn values v_n = 2 (mu_n - 1) + s_n (T.814 7.3.8) of a row of quads, mu_n = magnitude >> plane,
// in the quads' sample order (7.3.1): values[4q + n] for sample n of quad q, from the magnitudes and
// signs of the quad row's two rows of `width` samples (`lower` null past the block's last row, its
// values then 0). An insignificant sample's value is meaningless (it sends none). Writes 2 * width
// values.
void quad_magsgn(const std::uint32_t* upper, const std::uint32_t* lower, const std::uint8_t* upper_negative,
                 const std::uint8_t* lower_negative, std::size_t width, int plane, std::uint32_t* values);

}  // namespace codec::ht::simd
