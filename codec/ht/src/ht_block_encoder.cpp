#include "codec/ht/ht_block_encoder.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <span>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "cleanup_encoder.h"
#include "block_geometry.h"
#include "block_simd.h"
#include "refinement_encoder.h"
#include "codec/t1/dead_zone.h"

namespace codec::ht {
namespace {

// The coefficient's magnitude in index units: the index plus, for irreversible coding, its fraction.
double value_of(const HtBlock& b, std::size_t i) {
  return static_cast<double>(b.magnitudes[i]) + (b.fractions.empty() ? 0.0 : b.fractions[i] / 256.0);
}

// 2^p for the planes a magnitude has (p < 32): exact, without a call to ldexp in the loops over
// samples and planes below.
constexpr std::array<double, 33> kPowersOfTwo = [] {
  std::array<double, 33> out{};
  double v = 1;
  for (double& x : out) {
    x = v;
    v *= 2;
  }
  return out;
}();
double two_to(int p) { return kPowersOfTwo[static_cast<std::size_t>(p)]; }

// Half the interval a decoder still has for a significant magnitude after a cleanup on plane p: the
// mid-point rule; at p = 0 the index is exact, and an irreversible coefficient is placed at
// index + 1/2 (as EBCOT's passes assume, codec/src/t1/distortion.h).
double half_interval(const HtBlock& b, int p) { return !b.fractions.empty() || p > 0 ? two_to(p) / 2 : 0.0; }

// Raising near-significant samples (README, "Raising near-significant samples"). A decoder rebuilds
// an index that is 0 at the last coded plane q as 0 and a significant one at the middle of its
// interval, so a sample v in [0.75, 1) u, u = 2^q, is nearer the rebuilt 1 (1.5 u) than 0. Where
// making it significant costs little, the encoder (which codes every plane down to q at once, not
// embedded as EBCOT is) codes it as u: in the last pass's terms, where the cleanup is that pass,
// samples of quads already significant (their sign and U_q bits, no quad codeword or MEL symbol of
// their own; T.814 7.3); where SigProp is, any sample it visits (a sign bit: its significance bit
// is sent either way; T.814 7.4). The thresholds are where 16 Kodak photographs' PSNR at equal
// bytes peaked (README). Only irreversible blocks: a reversible one's indices are the data.
constexpr double kCleanupRaiseFrom = 0.9;
constexpr double kSigPropRaiseFrom = 0.85;

// The threshold `from` 2^q in 256ths of an index (magnitude * 256 + fraction reaches it).
std::int32_t raise_threshold(int q, double from) {
  return static_cast<std::int32_t>(std::ceil(from * std::ldexp(256.0, q)));
}

// Each raised v (below u = 2^p) leaves (v - 1.5 u)^2 = v^2 + 2.25 u^2 - 3 u v: the sum of
// 2.25 u^2 - 3 u v over them.
double raised_error_change(const HtBlock& b, int p, std::span<const std::size_t> raised) {
  const double u = two_to(p);
  double sum = 0;
  for (const std::size_t i : raised) sum += 2.25 * u * u - 3 * u * value_of(b, i);
  return sum;
}

// Lowering quads' exponents (README, "Lowering quads' exponents"; cleanup_encoder.h): a quad's
// U_q, the bits each of its significant samples sends, is set by its largest exponent E. Where its
// samples at E all sit just above the smallest index E has (2^(E - 2) + 1; offsets under a tenth
// of a step per significant sample, simd::adjust_quad_row) and kappa, the exponent predicted from
// the row above, does not hold U_q up anyway, coding them one index lower saves a bit per
// significant sample. Each lowered v = (mu + d) u leaves (d + 1/2)^2 u^2 instead of (d - 1/2)^2 u^2
// after the cleanup (2 d u^2 more), and after MagRef, whose bit is then 1, (d + 1/4)^2 u^2 instead
// of (d - 1/4)^2 u^2 (d u^2 more: MagRef's decrease grows by d u^2). Planes up to 23 (the
// offsets' arithmetic), irreversible blocks only; raising too.
constexpr int kHighestAdjustedCleanup = 23;

// The sum of d u^2 over the lowered samples.
double lowered_offsets(const HtBlock& b, int p, std::span<const std::size_t> lowered) {
  const std::uint32_t low_bits = (std::uint32_t{1} << p) - 1;
  double sum = 0;
  for (const std::size_t i : lowered) sum += (b.magnitudes[i] & low_bits) + b.fractions[i] / 256.0;
  return sum * two_to(p);
}

// SigProp raising on plane q (simd::stripe_columns): where the block's signs and fractions allow.
SigPropRaise sigprop_raise(const HtBlock& b, int p) {
  if (b.fractions.empty() || !b.signs_of_zeros || p > 15) return {};
  return {b.fractions, raise_threshold(p - 1, kSigPropRaiseFrom)};
}

// Appends the SigProp and MagRef passes of plane p - 1 to a block whose cleanup on plane p is
// `out`'s one pass: the refinement segment after the cleanup segment, each pass terminated (it
// ends its stream) and its distortion decrease measured on the samples it changes (MagRef's
// given, from simd::cleanup_errors).
void add_refinement_passes(const HtBlock& b, int p, t1::Distortion distortion, double magref_decrease,
                           std::span<const std::size_t> lowered, t1::EncodedBlock& out) {
  const RefinementSegment segment =
      encode_refinement(b.magnitudes, b.negative, b.width, b.height, p, sigprop_raise(b, p), lowered);
  // A sample SigProp makes significant was below 2^p (a decoder had it as 0: error v^2) and is
  // known at p - 1 as index 1 (rebuilt at a = 2^(p-1) + half(p - 1): error (v - a)^2), so it buys
  // v^2 - (v - a)^2 = a (2 v - a): the pass buys a (2 sum(v) - n a) over its n samples.
  double sigprop_decrease = 0;
  if (distortion == t1::Distortion::Measured) {
    double sum = 0;
    for (const std::size_t i : segment.became_significant) sum += value_of(b, i);
    const double a = two_to(p - 1) + half_interval(b, p - 1);
    sigprop_decrease = a * (2 * sum - static_cast<double>(segment.became_significant.size()) * a);
  }
  const std::size_t cleanup_bytes = out.data.size();
  out.data.reserve(cleanup_bytes + segment.bytes.size());
  out.data.insert(out.data.end(), segment.bytes.begin(), segment.bytes.end());
  out.passes.push_back(t1::PassInfo{cleanup_bytes + segment.sigprop_bytes, sigprop_decrease, true});
  out.passes.push_back(t1::PassInfo{out.data.size(), magref_decrease, true});
}

}  // namespace

namespace {

// Sign and magnitude of `count` indices into the block from `first` on; returns their OR.
std::uint32_t split_signs(const std::int32_t* indices, std::size_t count, std::uint32_t* magnitudes,
                          std::uint8_t* negative) {
  std::uint32_t all = 0;
  for (std::size_t i = 0; i < count; ++i) {
    const std::int32_t c = indices[i];
    magnitudes[i] =
        c < 0 ? static_cast<std::uint32_t>(0) - static_cast<std::uint32_t>(c) : static_cast<std::uint32_t>(c);
    negative[i] = c < 0 ? 1 : 0;
    all |= magnitudes[i];
  }
  return all;
}

// HtBlock's per-sample bit lengths, from its magnitudes.
void measure_bit_lengths(HtBlock& b) {
  b.lengths.resize(b.magnitudes.size());
  b.lengths_below_top.resize(b.magnitudes.size());
  simd::bit_lengths(b.magnitudes.data(), b.magnitudes.size(), b.lengths.data(), b.lengths_below_top.data());
}

// A reused block's buffers sized for n samples: kept as they are when they already hold n (every
// value is overwritten by the load), so that same-sized blocks need no clearing.
void size_buffers(HtBlock& b, int width, int height, bool with_fractions) {
  const std::size_t n = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  b.width = width;
  b.height = height;
  b.energy_bound = std::numeric_limits<double>::infinity();  // a float load sets its own
  b.signs_of_zeros = with_fractions;                         // only a float load has fractions, and it keeps every sign
  b.magnitudes.resize(n);
  b.negative.resize(n);
  b.lengths.resize(n);
  b.lengths_below_top.resize(n);
  if (with_fractions)
    b.fractions.resize(n);
  else
    b.fractions.clear();  // empty: reversible
}

}  // namespace

HtBlock load_ht_block(std::span<const std::int32_t> coefficients, int width, int height,
                      std::span<const std::uint8_t> fractions) {
  check_size(width, height);
  const auto n = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  if (coefficients.size() != n) throw std::invalid_argument("HT block: expected width * height coefficients");
  if (!fractions.empty() && fractions.size() != n)
    throw std::invalid_argument("HT block: expected one fraction per coefficient");
  HtBlock b{width, height, std::vector<std::uint32_t>(n), std::vector<std::uint8_t>(n), {}, 0, {}, {}};
  const std::uint32_t all = split_signs(coefficients.data(), n, b.magnitudes.data(), b.negative.data());
  b.fractions.assign(fractions.begin(), fractions.end());
  b.bit_planes = static_cast<int>(std::bit_width(all));
  measure_bit_lengths(b);
  return b;
}

void load_ht_block(const t1::IntegerBlock& block, HtBlock& b) {
  check_size(block.width, block.height);
  size_buffers(b, block.width, block.height, false);
  const auto w = static_cast<std::size_t>(block.width);
  std::uint32_t all = 0;
  for (int y = 0; y < block.height; ++y)
    all |= split_signs(block.origin + y * block.stride, w, b.magnitudes.data() + static_cast<std::size_t>(y) * w,
                       b.negative.data() + static_cast<std::size_t>(y) * w);
  b.bit_planes = static_cast<int>(std::bit_width(all));
  measure_bit_lengths(b);
}

void load_ht_block(const t1::FloatBlock& block, HtBlock& b) {
  check_size(block.width, block.height);
  size_buffers(b, block.width, block.height, true);
  const auto w = static_cast<std::size_t>(block.width);
  // Cold rows a plane's width apart: every line asked for up front (as t1's survey_float_block).
  constexpr std::size_t kLine = 64 / sizeof(float);
  for (int y = 0; y < block.height; ++y)
    for (std::size_t x = 0; x < w; x += kLine) __builtin_prefetch(block.origin + y * block.stride + x);
  std::uint32_t all = 0;
  double squares = 0;
  for (int y = 0; y < block.height; ++y) {
    const std::size_t base = static_cast<std::size_t>(y) * w;
    float row_squares = 0;
    all |= simd::quantize_row(block.origin + y * block.stride, w, block.inverse_step, b.magnitudes.data() + base,
                              b.negative.data() + base, b.fractions.data() + base, b.lengths.data() + base,
                              b.lengths_below_top.data() + base, &row_squares);
    squares += row_squares;
  }
  b.bit_planes = static_cast<int>(std::bit_width(all));
  // A float sum of at most 1024 non-negative terms is within 1024 * 2^-24 (6e-5) of the exact one.
  b.energy_bound = squares * (1 + 1e-4);
}

HtBlock load_ht_block(const t1::IntegerBlock& block) {
  HtBlock b;
  load_ht_block(block, b);
  return b;
}

HtBlock load_ht_block(const t1::FloatBlock& block) {
  HtBlock b;
  load_ht_block(block, b);
  return b;
}

t1::EncodedBlock encode_ht_block(const HtBlock& b, int magnitude_bitplanes, int cleanup_plane,
                                 t1::Distortion distortion, HtPasses passes) {
  if (magnitude_bitplanes < 1 || magnitude_bitplanes > 31)
    throw std::invalid_argument("HT block: Mb must be 1..31, not " + std::to_string(magnitude_bitplanes));
  if (cleanup_plane < 0 || cleanup_plane >= magnitude_bitplanes)
    throw std::invalid_argument("HT block: the cleanup plane must be 0..Mb - 1, not " + std::to_string(cleanup_plane));
  t1::EncodedBlock out;
  out.bit_planes = b.bit_planes;
  if (out.bit_planes > magnitude_bitplanes)
    throw std::invalid_argument("HT block: a magnitude needs " + std::to_string(out.bit_planes) +
                                " bit-planes, over Mb = " + std::to_string(magnitude_bitplanes));
  const bool measured = distortion == t1::Distortion::Measured;
  const bool refined = passes == HtPasses::CleanupAndRefinement && cleanup_plane > 0;
  const simd::CleanupErrors sums =
      simd::cleanup_errors(b.magnitudes.data(), b.fractions.empty() ? nullptr : b.fractions.data(), b.magnitudes.size(),
                           cleanup_plane, half_interval(b, 0), measured && refined);
  out.energy = sums.energy;
  if (out.bit_planes <= cleanup_plane) {
    out.missing_msbs = magnitude_bitplanes;
    return out;
  }
  // With refinement passes after it the cleanup raises nothing: SigProp gets those samples for two
  // bits, rebuilt nearer (0.75 u), where MagRef would leave a raised one at 1.25 u. Raising needs the
  // signs of zero indices.
  thread_local std::vector<std::size_t> raised, lowered;
  raised.clear();
  lowered.clear();
  const bool raises = !refined && b.signs_of_zeros;
  const CleanupAdjustment adjustment{
      b.fractions, raises ? static_cast<std::uint32_t>(raise_threshold(cleanup_plane, kCleanupRaiseFrom)) : 0u, &raised,
      &lowered};
  const bool adjusts = !b.fractions.empty() && cleanup_plane <= kHighestAdjustedCleanup;
  out.data = encode_cleanup(b.magnitudes, b.negative, b.lengths, b.lengths_below_top, b.width, b.height, cleanup_plane,
                            adjusts ? &adjustment : nullptr);
  const double offsets = lowered_offsets(b, cleanup_plane, lowered);
  out.first_pass_planes = out.bit_planes - cleanup_plane;
  out.missing_msbs = magnitude_bitplanes - 1 - cleanup_plane;
  const double decrease =
      measured ? sums.energy - sums.after_cleanup - raised_error_change(b, cleanup_plane, raised) - 2 * offsets : 0.0;
  out.passes.push_back(t1::PassInfo{out.data.size(), decrease, true});
  if (refined) add_refinement_passes(b, cleanup_plane, distortion, sums.refined + offsets, lowered, out);
  return out;
}

// Planes are at most 31, so every per-plane array of the statistics lives on the stack (no
// allocation per block): 32 planes and the entry for nothing coded.
constexpr std::size_t kMaxEntries = 33;

std::vector<PlaneStatistics> plane_counts(const HtBlock& b) {
  const int planes = b.bit_planes;
  std::vector<PlaneStatistics> out(static_cast<std::size_t>(planes) + 1);
  // Counts, quad by quad (T.814 7.3.1: 2x2 quads, samples outside the block insignificant). On plane
  // p a quad whose largest magnitude L has bit length l > p is significant; each of its samples of
  // bit length n > p is, and sends U = bit_width(2 (L >> p) - 1) = l - p + [p < t] bits (T.814
  // 7.3.7), t the bit length of L without its top bit (L >> p is a power of two exactly when
  // p >= t). So every count is a sum of terms constant or linear in p over a range of planes, and
  // is gathered with difference arrays in one visit per sample: quads[p] and samples[p] count,
  // bits[p] = top[p] - p * samples[p] + extra[p].
  // The columns that whole SIMD chunks of quads cover are counted plane by plane in SIMD
  // (simd::quad_counts); the rest, narrow blocks' and the columns past the last chunk, so.
  std::array<std::int64_t, kMaxEntries> quad_ends{}, sample_ends{}, top_ends{}, extra_ends{};
  std::array<std::int64_t, kMaxEntries> quads{}, samples{}, tops{}, extras{};
  const auto w = static_cast<std::size_t>(b.width);
  const std::size_t covered =
      simd::quad_counts(b.lengths.data(), b.lengths_below_top.data(), w, static_cast<std::size_t>(b.height), planes,
                        quads.data(), samples.data(), tops.data(), extras.data());
  std::int64_t quad_count = 0, sample_count = 0, top_sum = 0, extra_count = 0;
  for (int y0 = 0; y0 < b.height && covered < w; y0 += 2) {
    const std::uint32_t* upper = b.magnitudes.data() + static_cast<std::size_t>(y0) * w;
    const std::uint32_t* lower = y0 + 1 < b.height ? upper + w : nullptr;  // none below the last odd row
    const std::uint8_t* upper_lengths = b.lengths.data() + static_cast<std::size_t>(y0) * w;
    const std::uint8_t* lower_lengths = upper_lengths + w;
    for (int x0 = static_cast<int>(covered); x0 < b.width; x0 += 2) {
      const bool right = x0 + 1 < b.width;
      const std::uint32_t m[4] = {upper[x0], lower ? lower[x0] : 0u, right ? upper[x0 + 1] : 0u,
                                  lower && right ? lower[x0 + 1] : 0u};
      const int lengths[4] = {upper_lengths[x0], lower ? lower_lengths[x0] : 0, right ? upper_lengths[x0 + 1] : 0,
                              lower && right ? lower_lengths[x0 + 1] : 0};
      const std::uint32_t largest = std::max(std::max(m[0], m[1]), std::max(m[2], m[3]));
      const int length = std::max(std::max(lengths[0], lengths[1]), std::max(lengths[2], lengths[3]));
      if (length == 0) continue;
      const int below_top = static_cast<int>(std::bit_width(largest & ~(std::uint32_t{1} << (length - 1))));
      ++quad_count;
      --quad_ends[static_cast<std::size_t>(length)];
      // All four samples, without a branch: an insignificant one (length 0, or outside the block)
      // enters and leaves every count at plane 0, so it counts for no plane.
      sample_count += 4;
      top_sum += 4 * static_cast<std::int64_t>(length);
      extra_count += 4;
      for (const int sample_length : lengths) {
        --sample_ends[static_cast<std::size_t>(sample_length)];
        top_ends[static_cast<std::size_t>(sample_length)] -= length;
        --extra_ends[static_cast<std::size_t>(std::min(below_top, sample_length))];
      }
    }
  }
  std::array<std::int64_t, kMaxEntries> bits{};
  for (int p = 0; p < planes; ++p) {
    const auto i = static_cast<std::size_t>(p);
    quad_count += quad_ends[i];
    sample_count += sample_ends[i];
    top_sum += top_ends[i];
    extra_count += extra_ends[i];
    quads[i] += quad_count;
    samples[i] += sample_count;
    bits[i] = tops[i] + top_sum - static_cast<std::int64_t>(p) * samples[i] + extras[i] + extra_count;
  }
  for (int p = 0; p < planes; ++p) {
    out[static_cast<std::size_t>(p)].significant_quads = static_cast<double>(quads[static_cast<std::size_t>(p)]);
    out[static_cast<std::size_t>(p)].significant_samples = static_cast<double>(samples[static_cast<std::size_t>(p)]);
    out[static_cast<std::size_t>(p)].magnitude_bits = static_cast<double>(bits[static_cast<std::size_t>(p)]);
  }
  return out;
}

void add_plane_errors(const HtBlock& b, std::vector<PlaneStatistics>& statistics, int lowest_plane) {
  const int planes = b.bit_planes;
  // Errors, plane by plane over all samples in SIMD: a magnitude below 2^p leaves its whole value,
  // one at or above it its residual at p.
  std::array<double, kMaxEntries> errors{};
  lowest_plane = std::clamp(lowest_plane, 0, planes);
  simd::plane_errors(b.magnitudes.data(), b.fractions.empty() ? nullptr : b.fractions.data(), b.magnitudes.size(),
                     planes, half_interval(b, 0), lowest_plane, errors.data());
  for (int p = 0; p <= planes; ++p)
    statistics[static_cast<std::size_t>(p)].error = errors[static_cast<std::size_t>(std::max(p, lowest_plane))];
}

std::vector<PlaneStatistics> plane_statistics(const HtBlock& b) {
  std::vector<PlaneStatistics> out = plane_counts(b);
  add_plane_errors(b, out, 0);
  return out;
}

t1::EncodedBlock encode_ht_block(std::span<const std::int32_t> coefficients, int width, int height,
                                 int magnitude_bitplanes, int cleanup_plane, std::span<const std::uint8_t> fractions,
                                 t1::Distortion distortion) {
  return encode_ht_block(load_ht_block(coefficients, width, height, fractions), magnitude_bitplanes, cleanup_plane,
                         distortion);
}

t1::EncodedBlock encode_ht_block(const t1::IntegerBlock& block, int magnitude_bitplanes, int cleanup_plane,
                                 t1::Distortion distortion) {
  return encode_ht_block(load_ht_block(block), magnitude_bitplanes, cleanup_plane, distortion);
}

t1::EncodedBlock encode_ht_block(const t1::FloatBlock& block, int magnitude_bitplanes, int cleanup_plane,
                                 t1::Distortion distortion) {
  return encode_ht_block(load_ht_block(block), magnitude_bitplanes, cleanup_plane, distortion);
}

}  // namespace codec::ht
