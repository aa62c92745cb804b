// Highway's foreach_target re-includes this file once per SIMD target.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "block_simd.cpp"  // found through the src include directory
#include <hwy/foreach_target.h>              // must precede highway.h
#include <hwy/highway.h>

#include <algorithm>
#include <bit>

#include "block_simd.h"
#include "codec/t1/dead_zone.h"

HWY_BEFORE_NAMESPACE();
namespace codec::ht::simd {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

std::uint32_t QuantizeRow(const float* HWY_RESTRICT row, std::size_t n, float inverse_step,
                          std::uint32_t* HWY_RESTRICT magnitude, std::uint8_t* HWY_RESTRICT negative,
                          std::uint8_t* HWY_RESTRICT fraction, std::uint8_t* HWY_RESTRICT length,
                          std::uint8_t* HWY_RESTRICT length_below_top, float* HWY_RESTRICT squares) {
  const hn::ScalableTag<float> df;
  const hn::RebindToSigned<decltype(df)> di;
  const hn::RebindToUnsigned<decltype(df)> du;
  const hn::Rebind<std::uint8_t, decltype(di)> d8;
  const std::size_t N = hn::Lanes(df);
  const auto inverse = hn::Set(df, inverse_step);
  const auto largest = hn::Set(df, t1::kLargestMagnitude);
  const auto to_256ths = hn::Set(df, 256.0f);
  const auto zero = hn::Zero(di), top = hn::Set(di, 255), one = hn::Set(di, 1);
  // Bit lengths from the scaled magnitude m's float exponent: floor(m) has bit length e - 126 for
  // m >= 1 (e its exponent field, 127 + floor(log2 m)), and a field of 126 or less means m < 1,
  // index 0. Without its top bit the index is floor(m - 2^floor(log2 m)), the difference exact (m
  // is below twice that power), so its length comes alike.
  const auto exponent_bias = hn::Set(di, 126), sign_and_exponent = hn::Set(di, static_cast<std::int32_t>(0xFF800000u));
  const auto length_of = [&](auto value) {
    return hn::Max(hn::Sub(hn::ShiftRight<23>(hn::BitCast(di, value)), exponent_bias), zero);
  };
  auto any = hn::Zero(di);
  auto square_sum = hn::Zero(df);
  std::size_t i = 0;
  for (; i + N <= n; i += N) {
    const auto c = hn::LoadU(df, row + i);
    auto m = hn::Mul(hn::Abs(c), inverse);
    m = hn::IfThenElse(hn::Lt(m, largest), m, largest);  // NaN: the clamp, as scaled_magnitude
    square_sum = hn::MulAdd(m, m, square_sum);
    const auto q = hn::ConvertTo(di, m);  // m >= 0: truncation is the floor
    const auto f = hn::ConvertTo(di, hn::Mul(hn::Sub(m, hn::ConvertTo(df, q)), to_256ths));
    hn::StoreU(hn::BitCast(du, q), du, magnitude + i);
    hn::StoreU(hn::DemoteTo(d8, hn::Min(hn::Max(f, zero), top)), d8, fraction + i);
    const auto is_negative = hn::RebindMask(di, hn::Lt(c, hn::Zero(df)));
    hn::StoreU(hn::DemoteTo(d8, hn::IfThenElseZero(is_negative, one)), d8, negative + i);
    const auto power = hn::BitCast(df, hn::And(hn::BitCast(di, m), sign_and_exponent));
    hn::StoreU(hn::DemoteTo(d8, length_of(m)), d8, length + i);
    hn::StoreU(hn::DemoteTo(d8, length_of(hn::Sub(m, power))), d8, length_below_top + i);
    any = hn::Or(any, q);
  }
  HWY_ALIGN std::int32_t lanes[hn::MaxLanes(di)];
  hn::Store(any, di, lanes);
  std::uint32_t all = 0;
  for (std::size_t k = 0; k < N; ++k) all |= static_cast<std::uint32_t>(lanes[k]);
  float sum = hn::GetLane(hn::SumOfLanes(df, square_sum));
  for (; i < n; ++i) {
    const std::int32_t index = t1::quantize(row[i], inverse_step, fraction[i]);
    const double value = static_cast<double>(index < 0 ? -index : index) + fraction[i] / 256.0;
    sum += static_cast<float>(value * value);
    const std::uint32_t m = static_cast<std::uint32_t>(index < 0 ? -index : index);
    magnitude[i] = m;
    negative[i] = row[i] < 0 ? 1 : 0;  // a zero index's sign too (HtBlock::signs_of_zeros)
    const int l = static_cast<int>(std::bit_width(m));
    length[i] = static_cast<std::uint8_t>(l);
    length_below_top[i] = static_cast<std::uint8_t>(std::bit_width(l > 0 ? m ^ (std::uint32_t{1} << (l - 1)) : 0u));
    all |= m;
  }
  *squares = sum;
  return all;
}

CleanupErrors CleanupErrorSums(const std::uint32_t* HWY_RESTRICT magnitude, const std::uint8_t* HWY_RESTRICT fraction,
                               std::size_t n, int p, double half_at_zero, bool refinement) {
  const hn::ScalableTag<double> dd;
  const hn::Rebind<std::int32_t, decltype(dd)> di;
  const hn::Rebind<std::uint8_t, decltype(dd)> d8;
  const std::size_t N = hn::Lanes(dd);
  auto half = [&](int plane) {
    return plane > 0 ? static_cast<double>(std::uint32_t{1} << (plane - 1)) : half_at_zero;
  };
  const auto low_bits = static_cast<std::int32_t>((std::uint32_t{1} << p) - 1);
  const std::int32_t finer_bits = p > 0 ? low_bits >> 1 : 0;
  const auto mask = hn::Set(di, low_bits), finer_mask = hn::Set(di, finer_bits), one = hn::Set(di, 1);
  const auto h = hn::Set(dd, half(p)), finer_h = hn::Set(dd, half(p > 0 ? p - 1 : 0));
  const auto to_units = hn::Set(dd, 1.0 / 256);
  auto energy = hn::Zero(dd), after = hn::Zero(dd), refined = hn::Zero(dd);
  std::size_t i = 0;
  for (; i + N <= n; i += N) {
    const auto m = hn::BitCast(di, hn::LoadU(hn::RebindToUnsigned<decltype(di)>(), magnitude + i));
    const auto offset =
        fraction ? hn::Mul(hn::PromoteTo(dd, hn::PromoteTo(di, hn::LoadU(d8, fraction + i))), to_units) : hn::Zero(dd);
    const auto v = hn::Add(hn::PromoteTo(dd, m), offset);
    const auto significant = hn::PromoteTo(dd, hn::IfThenElseZero(hn::Gt(m, mask), one));  // 1.0 or 0.0
    const auto t = hn::Sub(hn::Add(hn::PromoteTo(dd, hn::And(m, mask)), offset), h);
    const auto e = hn::MulAdd(significant, hn::Sub(t, v), v);
    energy = hn::MulAdd(v, v, energy);
    after = hn::MulAdd(e, e, after);
    if (refinement) {
      const auto finer = hn::Sub(hn::Add(hn::PromoteTo(dd, hn::And(m, finer_mask)), offset), finer_h);
      refined = hn::MulAdd(significant, hn::Sub(hn::Mul(t, t), hn::Mul(finer, finer)), refined);
    }
  }
  CleanupErrors out;
  out.energy = hn::GetLane(hn::SumOfLanes(dd, energy));
  out.after_cleanup = hn::GetLane(hn::SumOfLanes(dd, after));
  out.refined = hn::GetLane(hn::SumOfLanes(dd, refined));
  for (; i < n; ++i) {
    const std::uint32_t m = magnitude[i];
    const double offset = fraction ? fraction[i] / 256.0 : 0.0;
    const double v = static_cast<double>(m) + offset;
    out.energy += v * v;
    if (m <= static_cast<std::uint32_t>(low_bits)) {
      out.after_cleanup += v * v;
      continue;
    }
    const double t = static_cast<double>(m & static_cast<std::uint32_t>(low_bits)) + offset - half(p);
    out.after_cleanup += t * t;
    if (refinement) {
      const double finer = static_cast<double>(m & static_cast<std::uint32_t>(finer_bits)) + offset - half(p - 1);
      out.refined += t * t - finer * finer;
    }
  }
  return out;
}

void PlaneErrors(const std::uint32_t* HWY_RESTRICT magnitude, const std::uint8_t* HWY_RESTRICT fraction, std::size_t n,
                 int planes, double half_at_zero, int lowest_plane, double* HWY_RESTRICT error) {
  const hn::ScalableTag<double> dd;
  const hn::Rebind<std::int32_t, decltype(dd)> di;  // as many int32 lanes as doubles
  const hn::RebindToUnsigned<decltype(di)> du;
  const hn::Rebind<std::uint8_t, decltype(dd)> d8;
  const hn::ScalableTag<float> df;  // a chunk: one vector of floats
  const hn::RebindToSigned<decltype(df)> dfi;
  const hn::RebindToUnsigned<decltype(df)> dfu;
  const hn::Rebind<std::uint8_t, decltype(df)> df8;
  const auto to_units = hn::Set(dd, 1.0 / 256);
  // Each sample's fraction below its index, as a value in [0, 1) (exact: a multiple of 1/256).
  auto offset_at = [&](std::size_t at) {
    return fraction ? hn::Mul(hn::PromoteTo(dd, hn::PromoteTo(di, hn::LoadU(d8, fraction + at))), to_units)
                    : hn::Zero(dd);
  };
  const std::size_t N = hn::Lanes(dd);
  constexpr int kMaxPlanes = 32;
  using V = decltype(hn::Zero(dd));
  HWY_ALIGN double halves[kMaxPlanes + 1];
  for (int p = 0; p <= planes; ++p) halves[p] = p > 0 ? static_cast<double>(std::uint64_t{1} << (p - 1)) : half_at_zero;
  for (int p = 0; p <= planes; ++p) error[p] = 0;
  // The samples in segments of up to kSegment, each in chunks of a float vector's lanes. A chunk
  // counts for plane p as a whole (every sample insignificant: its values' squares, summed in
  // double, exactly) when its largest magnitude is shorter than p + 1 bits, and sample by sample
  // otherwise; it is visited only for the planes below its largest length, not for every plane of
  // the block (most of a block's samples are far smaller than its largest). The chunks are ordered
  // by that length, longest first, so that the chunks of plane p are a prefix of the order: the
  // plane's loop keeps its sums in registers and has no test per chunk.
  // The sample-by-sample part is in float, twice the lanes of double: these errors only estimate
  // (ht_rate.cpp: which planes to code, which blocks to skip), and float's 24-bit mantissa leaves
  // each sum within some 1e-6 of the exact one; the energy (plane `planes`) stays exact.
  constexpr std::size_t kSegment = 1024;  // samples
  HWY_ALIGN float values[kSegment];
  HWY_ALIGN double whole[(kMaxPlanes + 1) * hn::MaxLanes(dd)];
  std::uint8_t longest[kSegment];
  std::uint16_t order[kSegment];
  const std::size_t C = hn::Lanes(df);
  const auto float_units = hn::Set(df, 1.0f / 256);
  std::size_t i = 0;
  while (i + C <= n) {
    const std::size_t chunks = std::min(kSegment, n - i) / C;
    std::size_t of_length[kMaxPlanes + 2] = {};  // chunks by the bit length of their largest magnitude
    std::fill(whole, whole + (kMaxPlanes + 1) * N, 0.0);
    int longest_of_all = 0;
    for (std::size_t c = 0; c < chunks; ++c) {
      const std::size_t at = i + c * C;
      // Magnitudes are below 2^31, so they convert as int32.
      const auto m = hn::BitCast(dfi, hn::LoadU(dfu, magnitude + at));
      auto value = hn::ConvertTo(df, m);
      if (fraction)
        value = hn::MulAdd(hn::ConvertTo(df, hn::PromoteTo(dfi, hn::LoadU(df8, fraction + at))), float_units, value);
      hn::Store(value, df, values + c * C);
      const int length =
          static_cast<int>(std::bit_width(static_cast<std::uint32_t>(hn::GetLane(hn::MaxOfLanes(dfi, m)))));
      longest[c] = static_cast<std::uint8_t>(length);
      ++of_length[length];
      longest_of_all = std::max(longest_of_all, length);
      V w = hn::Load(dd, whole + static_cast<std::size_t>(length) * N);
      for (std::size_t j = 0; j < C; j += N) {
        const auto exact =
            hn::Add(hn::PromoteTo(dd, hn::BitCast(di, hn::LoadU(du, magnitude + at + j))), offset_at(at + j));
        w = hn::MulAdd(exact, exact, w);
      }
      hn::Store(w, dd, whole + static_cast<std::size_t>(length) * N);
    }
    // longer[L]: the chunks whose largest magnitude is longer than L bits. Plane L visits those,
    // and in the order by length, longest first (a counting sort), the chunks of length L start there.
    std::size_t longer[kMaxPlanes + 2];
    longer[kMaxPlanes + 1] = 0;
    for (int length = kMaxPlanes; length >= 0; --length) longer[length] = longer[length + 1] + of_length[length + 1];
    std::size_t slot[kMaxPlanes + 2];
    std::copy(longer, longer + kMaxPlanes + 2, slot);
    for (std::size_t c = 0; c < chunks; ++c) order[slot[longest[c]]++] = static_cast<std::uint16_t>(c * C);
    double whole_so_far = 0;
    for (int p = 0; p <= planes; ++p) {
      whole_so_far += hn::GetLane(hn::SumOfLanes(dd, hn::Load(dd, whole + static_cast<std::size_t>(p) * N)));
      error[p] += whole_so_far;
      if (p >= longest_of_all || p < lowest_plane) continue;
      // A sample of magnitude m and value v = m + offset (its fraction, in [0, 1)) is significant at p
      // when v >= 2^p, and leaves v - floor(v / 2^p) 2^p - half(p) = (m mod 2^p) + offset - half(p); an
      // insignificant one leaves v.
      const auto step = hn::Set(df, static_cast<float>(std::uint64_t{1} << p));
      const auto inverse_step = hn::Set(df, 1.0f / static_cast<float>(std::uint64_t{1} << p));
      const auto half = hn::Set(df, static_cast<float>(halves[p]));
      auto sum0 = hn::Zero(df), sum1 = hn::Zero(df);
      const std::size_t visited = longer[p];
      auto left_of = [&](const float* at) {
        const auto value = hn::Load(df, at);
        const auto above = hn::Floor(hn::Mul(value, inverse_step));
        const auto left = hn::Sub(hn::NegMulAdd(above, step, value), half);
        return hn::IfThenElse(hn::Ge(value, step), left, value);
      };
      std::size_t k = 0;
      for (; k + 2 <= visited; k += 2) {
        const auto left0 = left_of(values + order[k]), left1 = left_of(values + order[k + 1]);
        sum0 = hn::MulAdd(left0, left0, sum0);
        sum1 = hn::MulAdd(left1, left1, sum1);
      }
      if (k < visited) {
        const auto left = left_of(values + order[k]);
        sum0 = hn::MulAdd(left, left, sum0);
      }
      error[p] += static_cast<double>(hn::GetLane(hn::SumOfLanes(df, hn::Add(sum0, sum1))));
    }
    i += chunks * C;
  }
  for (; i < n; ++i) {
    const double value = static_cast<double>(magnitude[i]) + (fraction ? fraction[i] / 256.0 : 0.0);
    for (int p = lowest_plane; p <= planes; ++p) {
      const auto low_bits = static_cast<std::uint32_t>((std::uint64_t{1} << p) - 1);
      const double left =
          magnitude[i] <= low_bits ? value : value - (static_cast<double>(magnitude[i] & ~low_bits) + halves[p]);
      error[p] += left * left;
    }
  }
}

void BitLengths(const std::uint32_t* HWY_RESTRICT magnitude, std::size_t n, std::uint8_t* HWY_RESTRICT length,
                std::uint8_t* HWY_RESTRICT length_below_top) {
  const hn::ScalableTag<std::int32_t> di;
  const hn::Rebind<float, decltype(di)> df;
  const hn::Rebind<std::uint8_t, decltype(di)> d8;
  const std::size_t N = hn::Lanes(di);
  const auto zero = hn::Zero(di), one = hn::Set(di, 1), low_half = hn::Set(di, 0xFFFF);
  const auto exponent_bias = hn::Set(di, 126), sixteen = hn::Set(di, 16);
  // The bit length of x < 2^16 (exact as a float): its float's exponent field less 126; 0 for 0.
  const auto short_length = [&](auto x) {
    return hn::Max(hn::Sub(hn::ShiftRight<23>(hn::BitCast(di, hn::ConvertTo(df, x))), exponent_bias), zero);
  };
  // That of v < 2^31, from its high and low 16 bits.
  const auto bit_length = [&](auto v) {
    const auto high = hn::ShiftRight<16>(v);
    return hn::IfThenElse(hn::Gt(high, zero), hn::Add(short_length(high), sixteen), short_length(hn::And(v, low_half)));
  };
  std::size_t i = 0;
  for (; i + N <= n; i += N) {
    const auto v = hn::BitCast(di, hn::LoadU(hn::RebindToUnsigned<decltype(di)>(), magnitude + i));
    const auto l = bit_length(v);
    const auto top = hn::IfThenElseZero(hn::Gt(l, zero), hn::operator<<(one, hn::Sub(l, one)));
    hn::StoreU(hn::DemoteTo(d8, l), d8, length + i);
    hn::StoreU(hn::DemoteTo(d8, bit_length(hn::Xor(v, top))), d8, length_below_top + i);
  }
  for (; i < n; ++i) {
    const std::uint32_t m = magnitude[i];
    const int l = static_cast<int>(std::bit_width(m));
    length[i] = static_cast<std::uint8_t>(l);
    length_below_top[i] = static_cast<std::uint8_t>(std::bit_width(l > 0 ? m ^ (std::uint32_t{1} << (l - 1)) : 0u));
  }
}

void StripeColumns(const std::uint32_t* HWY_RESTRICT stripe, const std::uint8_t* HWY_RESTRICT fraction,
                   std::size_t width, std::size_t stride, int rows, int p, std::int32_t threshold,
                   std::uint8_t* HWY_RESTRICT columns) {
  const hn::ScalableTag<std::int32_t> di;
  const hn::Rebind<std::uint8_t, decltype(di)> d8;
  const std::size_t N = hn::Lanes(di);
  const auto below_plane = hn::Set(di, static_cast<std::int32_t>((std::uint32_t{1} << p) - 1));
  const auto one = hn::Set(di, 1), raise_from = hn::Set(di, threshold - 1);  // key > threshold - 1
  std::size_t x = 0;
  for (; x + N <= width; x += N) {
    auto code = hn::Zero(di);
    for (int r = 0; r < rows; ++r) {
      const std::size_t at = static_cast<std::size_t>(r) * stride + x;
      const auto v = hn::BitCast(di, hn::LoadU(hn::RebindToUnsigned<decltype(di)>(), stripe + at));
      const auto significant = hn::Gt(v, below_plane);  // magnitudes are below 2^31
      auto bit = hn::And(hn::ShiftRightSame(v, p - 1), one);
      if (fraction) {
        // Below 2^p the bit SigProp sends: whether v with its fraction reaches the threshold
        // (v < 2^p <= 2^15 here, so v * 256 + fraction fits).
        const auto key = hn::Or(hn::ShiftLeft<8>(v), hn::PromoteTo(di, hn::LoadU(d8, fraction + at)));
        bit = hn::IfThenElse(significant, bit, hn::IfThenElseZero(hn::Gt(key, raise_from), one));
      }
      code = hn::Or(code, hn::ShiftLeftSame(hn::Or(hn::IfThenElseZero(significant, one), hn::ShiftLeft<4>(bit)), r));
    }
    hn::StoreU(hn::DemoteTo(d8, code), d8, columns + x);
  }
  for (; x < width; ++x) {
    std::uint32_t code = 0;
    for (int r = 0; r < rows; ++r) {
      const std::size_t at = static_cast<std::size_t>(r) * stride + x;
      const std::uint32_t v = stripe[at];
      const bool significant = (v >> p) != 0;
      std::uint32_t bit = (v >> (p - 1)) & 1u;
      if (fraction && !significant) bit = (v << 8 | fraction[at]) >= static_cast<std::uint32_t>(threshold) ? 1u : 0u;
      code |= ((significant ? 1u : 0u) | bit << 4) << r;
    }
    columns[x] = static_cast<std::uint8_t>(code);
  }
}

void ColumnBitMasks(const std::uint8_t* HWY_RESTRICT columns, std::size_t width, std::size_t words,
                    std::uint64_t* HWY_RESTRICT masks) {
  std::fill(masks, masks + 8 * words, std::uint64_t{0});
  const hn::ScalableTag<std::uint8_t> d8;
  const std::size_t N = hn::Lanes(d8);
  // Whole vectors where their mask bits fill whole bytes (every u8 vector but the scalar target's).
  const std::size_t covered = N % 8 == 0 ? width / N * N : 0;
  // Bit by bit outermost: Highway allows StoreMaskBits to write up to 8 bytes on some targets (x86
  // writes exactly N / 8), past this bit's words into the next bit's, which are written after; the
  // buffer has 8 bytes to spare after the last bit's (header).
  for (int b = 0; b < 8; ++b) {
    auto* out = reinterpret_cast<std::uint8_t*>(masks + static_cast<std::size_t>(b) * words);
    const auto bit = hn::Set(d8, static_cast<std::uint8_t>(1u << b));
    for (std::size_t x = 0; x < covered; x += N)
      hn::StoreMaskBits(d8, hn::TestBit(hn::LoadU(d8, columns + x), bit), out + x / 8);
  }
  for (std::size_t x = covered; x < width; ++x)
    for (int b = 0; b < 8; ++b)
      masks[static_cast<std::size_t>(b) * words + x / 64] |= static_cast<std::uint64_t>((columns[x] >> b) & 1)
                                                             << (x % 64);
}

void QuadRowAnalysis(const std::uint8_t* HWY_RESTRICT above, const std::uint8_t* HWY_RESTRICT upper,
                     const std::uint8_t* HWY_RESTRICT lower, std::size_t quads, bool initial_row,
                     std::uint16_t* HWY_RESTRICT index, std::uint16_t* HWY_RESTRICT exponents) {
  const hn::ScalableTag<std::uint16_t> d;  // a lane per quad: its two columns' bytes, the left one low
  const std::size_t N = hn::Lanes(d);
  const auto low_byte = hn::Set(d, 0xFF), zero = hn::Zero(d), one = hn::Set(d, 1);
  const auto pairs = [&](const std::uint8_t* bytes) {
    return hn::LoadU(d, reinterpret_cast<const std::uint16_t*>(bytes));
  };
  const auto flag = [&](auto mask, int shift) {
    return hn::IfThenElseZero(mask, hn::Set(d, static_cast<std::uint16_t>(1u << shift)));
  };
  for (std::size_t q = 0; q < quads; q += N) {
    const std::size_t x = 2 * q;
    const auto top = pairs(upper + x), bottom = pairs(lower + x);
    // The quad's samples in the standard's order: left column top and bottom, right column.
    const auto s0 = hn::And(top, low_byte), s1 = hn::And(bottom, low_byte);
    const auto s2 = hn::ShiftRight<8>(top), s3 = hn::ShiftRight<8>(bottom);
    const auto rho = hn::Or(hn::Or(flag(hn::Ne(s0, zero), 0), flag(hn::Ne(s1, zero), 1)),
                            hn::Or(flag(hn::Ne(s2, zero), 2), flag(hn::Ne(s3, zero), 3)));
    const auto largest = hn::Max(hn::Max(s0, s1), hn::Max(s2, s3));
    hn::Vec<decltype(d)> context, kappa = one;
    if (initial_row) {
      // The quad to the left: its left column (far) and right column (near), rows y0 and y0 + 1.
      const auto left_top = pairs(upper + x - 2), left_bottom = pairs(lower + x - 2);
      const auto far = flag(hn::Ne(hn::And(hn::Or(left_top, left_bottom), low_byte), zero), 0);
      context = hn::Or(far, hn::Or(flag(hn::Ne(hn::ShiftRight<8>(left_top), zero), 1),
                                   flag(hn::Ne(hn::ShiftRight<8>(left_bottom), zero), 2)));
    } else {
      // Above: x0 - 1 and x0 (north), x0 + 1 and x0 + 2 (east); the column left of the quad (west).
      const auto north = pairs(above + x - 1), east = pairs(above + x + 1);
      const auto west = hn::And(hn::Or(pairs(upper + x - 1), pairs(lower + x - 1)), low_byte);
      context = hn::Or(flag(hn::Ne(north, zero), 0), hn::Or(flag(hn::Ne(west, zero), 1), flag(hn::Ne(east, zero), 2)));
      const auto above_largest = hn::Max(hn::Max(hn::And(north, low_byte), hn::ShiftRight<8>(north)),
                                         hn::Max(hn::And(east, low_byte), hn::ShiftRight<8>(east)));
      const auto several = hn::Ne(hn::And(rho, hn::Sub(rho, one)), zero);
      kappa = hn::IfThenElse(several, hn::Max(one, hn::SaturatedSub(above_largest, one)), one);
    }
    const auto bits = hn::Max(largest, kappa);
    const auto residual = hn::Sub(bits, kappa);
    const auto has_residual = hn::Ne(residual, zero);
    const auto at_top =
        hn::IfThenElseZero(has_residual, hn::Or(hn::Or(flag(hn::Eq(s0, bits), 0), flag(hn::Eq(s1, bits), 1)),
                                                hn::Or(flag(hn::Eq(s2, bits), 2), flag(hn::Eq(s3, bits), 3))));
    const auto code =
        hn::Or(hn::ShiftLeft<9>(context), hn::Or(hn::ShiftLeft<5>(rho), hn::Or(flag(has_residual, 4), at_top)));
    hn::StoreU(code, d, index + q);
    hn::StoreU(hn::Or(bits, hn::ShiftLeft<8>(residual)), d, exponents + q);
  }
}

void AdjustmentCodes(const std::uint32_t* HWY_RESTRICT magnitude, const std::uint8_t* HWY_RESTRICT fraction,
                     std::size_t n, int p, std::uint32_t raise_threshold, std::uint8_t* HWY_RESTRICT codes) {
  const hn::ScalableTag<std::uint32_t> d;
  const hn::Rebind<std::uint8_t, decltype(d)> d8;
  const std::size_t N = hn::Lanes(d);
  const std::uint32_t unit = std::uint32_t{1} << p;
  const auto low_bits = hn::Set(d, unit - 1), one = hn::Set(d, 1), two = hn::Set(d, 2), zero = hn::Zero(d);
  const auto largest = hn::Set(d, kLargestLoweringOffset), none = hn::Set(d, kNoAdjustment);
  const auto raise = hn::Set(d, kRaise), unit_v = hn::Set(d, unit);
  // Keys reach raise_threshold when raise_threshold - 1 < key; with a threshold of 0 (none) no key,
  // below 2^31, exceeds 2^31 - 1.
  const auto from = hn::Set(d, raise_threshold == 0 ? std::uint32_t{0x7FFFFFFF} : raise_threshold - 1);
  std::size_t i = 0;
  for (; i + N <= n; i += N) {
    const auto m = hn::LoadU(d, magnitude + i);
    const auto mu = hn::ShiftRightSame(m, p);
    const auto f = hn::PromoteTo(d, hn::LoadU(d8, fraction + i));
    // The smallest index of its exponent: mu >= 2 and mu - 1 a power of two.
    const auto smallest =
        hn::And(hn::Eq(hn::And(hn::Sub(mu, one), hn::Sub(mu, two)), zero), hn::Ne(hn::ShiftRight<1>(mu), zero));
    const auto offset = hn::ShiftRightSame(hn::Or(hn::ShiftLeft<8>(hn::And(m, low_bits)), f), p);
    // Below 2^p, m * 256 + fraction < 2^31 (p <= 23): signed compares are exact.
    const auto di = hn::RebindToSigned<decltype(d)>();
    const auto key = hn::BitCast(di, hn::Or(hn::ShiftLeft<8>(m), f));
    const auto raisable = hn::And(hn::RebindMask(d, hn::Lt(hn::BitCast(di, m), hn::BitCast(di, unit_v))),
                                  hn::RebindMask(d, hn::Gt(key, hn::BitCast(di, from))));
    const auto chosen = hn::IfThenElse(smallest, hn::Min(offset, largest), hn::IfThenElse(raisable, raise, none));
    hn::StoreU(hn::DemoteTo(d8, hn::BitCast(di, chosen)), d8, codes + i);
  }
  for (; i < n; ++i) {
    const std::uint32_t m = magnitude[i], mu = m >> p;
    const std::uint32_t offset = ((m & (unit - 1)) << 8 | fraction[i]) >> p;
    if (mu >= 2 && ((mu - 1) & (mu - 2)) == 0)
      codes[i] = static_cast<std::uint8_t>(std::min<std::uint32_t>(offset, kLargestLoweringOffset));
    else if (raise_threshold != 0 && mu == 0 && (m << 8 | fraction[i]) >= raise_threshold)
      codes[i] = kRaise;
    else
      codes[i] = kNoAdjustment;
  }
}

bool AdjustQuadRow(const std::uint8_t* HWY_RESTRICT above, std::uint8_t* HWY_RESTRICT upper,
                   std::uint8_t* HWY_RESTRICT lower, const std::uint8_t* HWY_RESTRICT upper_codes,
                   const std::uint8_t* HWY_RESTRICT lower_codes, std::size_t quads, bool initial_row,
                   std::uint16_t* HWY_RESTRICT pattern) {
  const hn::ScalableTag<std::uint16_t> d;  // a lane per quad: its two columns' bytes, the left one low
  const std::size_t N = hn::Lanes(d);
  const auto low_byte = hn::Set(d, 0xFF), zero = hn::Zero(d), one = hn::Set(d, 1);
  const auto denominator = hn::Set(d, static_cast<std::uint16_t>(kLowerDenominator)), full = hn::Set(d, 256);
  const auto raise = hn::Set(d, static_cast<std::uint16_t>(kRaise));
  const auto pairs = [&](const std::uint8_t* bytes) {
    return hn::LoadU(d, reinterpret_cast<const std::uint16_t*>(bytes));
  };
  const auto count = [&](auto mask) { return hn::IfThenElseZero(mask, one); };
  auto any = zero;
  for (std::size_t q = 0; q < quads; q += N) {
    const std::size_t x = 2 * q;
    const auto top = pairs(upper + x), bottom = pairs(lower + x);
    // The quad's samples in the standard's order: left column top and bottom, right column.
    hn::Vec<decltype(d)> s[4] = {hn::And(top, low_byte), hn::And(bottom, low_byte), hn::ShiftRight<8>(top),
                                 hn::ShiftRight<8>(bottom)};
    const auto top_codes = pairs(upper_codes + x), bottom_codes = pairs(lower_codes + x);
    const hn::Vec<decltype(d)> o[4] = {hn::And(top_codes, low_byte), hn::And(bottom_codes, low_byte),
                                       hn::ShiftRight<8>(top_codes), hn::ShiftRight<8>(bottom_codes)};
    const auto largest = hn::Max(hn::Max(s[0], s[1]), hn::Max(s[2], s[3]));
    // Raising first, in quads significant already: exponent 1 (index 1). Not past the row's quads.
    auto active = hn::Gt(largest, zero);
    if (quads - q < N) active = hn::And(active, hn::FirstN(d, quads - q));
    auto bits = zero;
    for (int k = 0; k < 4; ++k) {
      const auto here = hn::And(active, hn::Eq(o[k], raise));
      s[k] = hn::IfThenElse(here, one, s[k]);
      bits = hn::Or(bits, hn::ShiftLeftSame(count(here), 4 + k));
    }
    const auto significant = hn::Add(hn::Add(count(hn::Ne(s[0], zero)), count(hn::Ne(s[1], zero))),
                                     hn::Add(count(hn::Ne(s[2], zero)), count(hn::Ne(s[3], zero))));
    auto kappa = one;
    if (!initial_row) {
      // As quad_row_analysis: x0 - 1 .. x0 + 2 of the row above, with two significant samples or more.
      const auto north = pairs(above + x - 1), east = pairs(above + x + 1);
      const auto above_largest = hn::Max(hn::Max(hn::And(north, low_byte), hn::ShiftRight<8>(north)),
                                         hn::Max(hn::And(east, low_byte), hn::ShiftRight<8>(east)));
      kappa = hn::IfThenElse(hn::Gt(significant, one), hn::Max(one, hn::SaturatedSub(above_largest, one)), one);
    }
    auto offsets = zero;
    for (int k = 0; k < 4; ++k) offsets = hn::Add(offsets, hn::IfThenElseZero(hn::Eq(s[k], largest), o[k]));
    auto lowered = hn::And(hn::And(hn::Gt(largest, one), hn::Gt(largest, kappa)),
                           hn::Lt(hn::Mul(offsets, denominator), hn::Mul(significant, full)));
    if (quads - q < N) lowered = hn::And(lowered, hn::FirstN(d, quads - q));
    hn::Vec<decltype(d)> after[4];
    for (int k = 0; k < 4; ++k) {
      const auto here = hn::And(lowered, hn::Eq(s[k], largest));
      after[k] = hn::Sub(s[k], count(here));
      bits = hn::Or(bits, hn::ShiftLeftSame(count(here), k));
    }
    hn::StoreU(hn::Or(after[0], hn::ShiftLeft<8>(after[2])), d, reinterpret_cast<std::uint16_t*>(upper + x));
    hn::StoreU(hn::Or(after[1], hn::ShiftLeft<8>(after[3])), d, reinterpret_cast<std::uint16_t*>(lower + x));
    hn::StoreU(bits, d, pattern + q);
    any = hn::Or(any, bits);
  }
  return !hn::AllTrue(d, hn::Eq(any, zero));
}

void QuadMagSgn(const std::uint32_t* HWY_RESTRICT upper, const std::uint32_t* HWY_RESTRICT lower,
                const std::uint8_t* HWY_RESTRICT upper_negative, const std::uint8_t* HWY_RESTRICT lower_negative,
                std::size_t width, int plane, std::uint32_t* HWY_RESTRICT values) {
  const hn::ScalableTag<std::uint32_t> d;
  const hn::Rebind<std::uint8_t, decltype(d)> d8;
  const std::size_t N = hn::Lanes(d);
  const auto two = hn::Set(d, 2);
  // v = 2 (mu - 1) + s = 2 mu + s - 2, wrapping for an insignificant sample (never sent).
  const auto value_of = [&](const std::uint32_t* m, const std::uint8_t* negative, std::size_t x) {
    const auto mu = hn::ShiftRightSame(hn::LoadU(d, m + x), plane);
    return hn::Sub(hn::Add(hn::ShiftLeft<1>(mu), hn::PromoteTo(d, hn::LoadU(d8, negative + x))), two);
  };
  std::size_t x = 0;
  if (lower) {
    for (; x + N <= width; x += N)
      hn::StoreInterleaved2(value_of(upper, upper_negative, x), value_of(lower, lower_negative, x), d, values + 2 * x);
  }
  for (; x < width; ++x) {
    values[2 * x] = 2 * (upper[x] >> plane) + upper_negative[x] - 2;
    values[2 * x + 1] = lower ? 2 * (lower[x] >> plane) + lower_negative[x] - 2 : 0;
  }
}

std::size_t QuadCounts(const std::uint8_t* HWY_RESTRICT lengths, const std::uint8_t* HWY_RESTRICT tops,
                       std::size_t width, std::size_t height, int planes, std::int64_t* HWY_RESTRICT quads,
                       std::int64_t* HWY_RESTRICT samples, std::int64_t* HWY_RESTRICT top_sums,
                       std::int64_t* HWY_RESTRICT extras) {
  const hn::ScalableTag<std::uint16_t> d16;  // a lane per quad: its two columns' bytes
  // A quad's two columns as one 16-bit lane, the left one low (little-endian, as every target this
  // project builds for).
  const auto load_pairs = [&](const std::uint8_t* bytes) {
    return hn::LoadU(d16, reinterpret_cast<const std::uint16_t*>(bytes));
  };
  const std::size_t N = hn::Lanes(d16);
  const std::size_t covered = width / (2 * N) * (2 * N);
  if (covered == 0 || planes <= 0) return covered;
  // Per plane, four lane-wise sums: quads, samples, quad lengths and extra bits over the samples
  // significant at that plane. A lane adds at most 4 * 31 a row pair, and a block has at most 512
  // row pairs, so 16 bits hold them.
  constexpr int kMaxPlanes = 32;
  constexpr std::size_t kSums = 4;
  HWY_ALIGN std::uint16_t sums[kSums * kMaxPlanes * hn::MaxLanes(d16)];
  std::fill(sums, sums + kSums * static_cast<std::size_t>(planes) * N, std::uint16_t{0});
  const auto low_byte = hn::Set(d16, 0xFF);
  int deepest = 0;  // planes below the largest quad length seen
  for (std::size_t y0 = 0; y0 < height; y0 += 2) {
    const std::uint8_t* upper = lengths + y0 * width;
    const std::uint8_t* upper_tops = tops + y0 * width;
    const bool has_lower = y0 + 1 < height;
    for (std::size_t x = 0; x < covered; x += 2 * N) {
      const auto u = load_pairs(upper + x);
      const auto tu = load_pairs(upper_tops + x);
      const auto l = has_lower ? load_pairs(upper + width + x) : hn::Zero(d16);
      const auto tl = has_lower ? load_pairs(upper_tops + width + x) : hn::Zero(d16);
      // The quad's four samples: its columns are each lane's low and high byte.
      const auto a = hn::And(u, low_byte), b = hn::ShiftRight<8>(u);
      const auto c = hn::And(l, low_byte), d = hn::ShiftRight<8>(l);
      const auto length = hn::Max(hn::Max(a, b), hn::Max(c, d));
      const int longest = static_cast<int>(hn::GetLane(hn::MaxOfLanes(d16, length)));
      if (longest == 0) continue;
      deepest = std::max(deepest, longest);
      // t of the quad's largest magnitude: the largest t among its samples of the quad's length.
      const auto below_top = hn::Max(hn::Max(hn::IfThenElseZero(hn::Eq(a, length), hn::And(tu, low_byte)),
                                             hn::IfThenElseZero(hn::Eq(b, length), hn::ShiftRight<8>(tu))),
                                     hn::Max(hn::IfThenElseZero(hn::Eq(c, length), hn::And(tl, low_byte)),
                                             hn::IfThenElseZero(hn::Eq(d, length), hn::ShiftRight<8>(tl))));
      const auto ea = hn::Min(below_top, a), eb = hn::Min(below_top, b);
      const auto ec = hn::Min(below_top, c), ed = hn::Min(below_top, d);
      for (int p = 0; p < longest; ++p) {
        const auto plane = hn::Set(d16, static_cast<std::uint16_t>(p));
        std::uint16_t* at = sums + static_cast<std::size_t>(p) * kSums * N;
        // A true mask is all ones, -1: subtracting it counts one.
        const auto one_if = [&](auto v) { return hn::VecFromMask(d16, hn::Gt(v, plane)); };
        hn::Store(hn::Sub(hn::Load(d16, at), one_if(length)), d16, at);
        hn::Store(hn::Sub(hn::Sub(hn::Sub(hn::Sub(hn::Load(d16, at + N), one_if(a)), one_if(b)), one_if(c)), one_if(d)),
                  d16, at + N);
        const auto lengths_of_significant = hn::Add(
            hn::Add(hn::IfThenElseZero(hn::Gt(a, plane), length), hn::IfThenElseZero(hn::Gt(b, plane), length)),
            hn::Add(hn::IfThenElseZero(hn::Gt(c, plane), length), hn::IfThenElseZero(hn::Gt(d, plane), length)));
        hn::Store(hn::Add(hn::Load(d16, at + 2 * N), lengths_of_significant), d16, at + 2 * N);
        hn::Store(hn::Sub(hn::Sub(hn::Sub(hn::Sub(hn::Load(d16, at + 3 * N), one_if(ea)), one_if(eb)), one_if(ec)),
                          one_if(ed)),
                  d16, at + 3 * N);
      }
    }
  }
  for (int p = 0; p < deepest; ++p) {
    const std::uint16_t* at = sums + static_cast<std::size_t>(p) * kSums * N;
    std::int64_t totals[kSums] = {};
    for (std::size_t k = 0; k < kSums; ++k)
      for (std::size_t lane = 0; lane < N; ++lane) totals[k] += at[k * N + lane];
    quads[p] += totals[0];
    samples[p] += totals[1];
    top_sums[p] += totals[2];
    extras[p] += totals[3];
  }
  return covered;
}

}  // namespace HWY_NAMESPACE
}  // namespace codec::ht::simd
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace codec::ht::simd {
HWY_EXPORT(QuantizeRow);
HWY_EXPORT(PlaneErrors);
HWY_EXPORT(CleanupErrorSums);
HWY_EXPORT(BitLengths);
HWY_EXPORT(StripeColumns);
HWY_EXPORT(AdjustmentCodes);
HWY_EXPORT(AdjustQuadRow);
HWY_EXPORT(QuadCounts);
HWY_EXPORT(ColumnBitMasks);
HWY_EXPORT(QuadRowAnalysis);
HWY_EXPORT(QuadMagSgn);

void quad_magsgn(const std::uint32_t* upper, const std::uint32_t* lower, const std::uint8_t* upper_negative,
                 const std::uint8_t* lower_negative, std::size_t width, int plane, std::uint32_t* values) {
  HWY_DYNAMIC_DISPATCH(QuadMagSgn)(upper, lower, upper_negative, lower_negative, width, plane, values);
}

void quad_row_analysis(const std::uint8_t* above, const std::uint8_t* upper, const std::uint8_t* lower,
                       std::size_t quads, bool initial_row, std::uint16_t* index, std::uint16_t* exponents) {
  HWY_DYNAMIC_DISPATCH(QuadRowAnalysis)(above, upper, lower, quads, initial_row, index, exponents);
}

void column_bit_masks(const std::uint8_t* columns, std::size_t width, std::size_t words, std::uint64_t* masks) {
  HWY_DYNAMIC_DISPATCH(ColumnBitMasks)(columns, width, words, masks);
}

void stripe_columns(const std::uint32_t* stripe, const std::uint8_t* fraction, std::size_t width, std::size_t stride,
                    int rows, int p, std::int32_t threshold, std::uint8_t* columns) {
  HWY_DYNAMIC_DISPATCH(StripeColumns)(stripe, fraction, width, stride, rows, p, threshold, columns);
}

void adjustment_codes(const std::uint32_t* magnitude, const std::uint8_t* fraction, std::size_t n, int p,
                      std::uint32_t raise_threshold, std::uint8_t* codes) {
  HWY_DYNAMIC_DISPATCH(AdjustmentCodes)(magnitude, fraction, n, p, raise_threshold, codes);
}
bool adjust_quad_row(const std::uint8_t* above, std::uint8_t* upper, std::uint8_t* lower,
                     const std::uint8_t* upper_codes, const std::uint8_t* lower_codes, std::size_t quads,
                     bool initial_row, std::uint16_t* pattern) {
  return HWY_DYNAMIC_DISPATCH(AdjustQuadRow)(above, upper, lower, upper_codes, lower_codes, quads, initial_row,
                                             pattern);
}

std::size_t quad_counts(const std::uint8_t* lengths, const std::uint8_t* lengths_below_top, std::size_t width,
                        std::size_t height, int planes, std::int64_t* quads, std::int64_t* samples,
                        std::int64_t* top_sums, std::int64_t* extras) {
  return HWY_DYNAMIC_DISPATCH(QuadCounts)(lengths, lengths_below_top, width, height, planes, quads, samples, top_sums,
                                          extras);
}

void bit_lengths(const std::uint32_t* magnitude, std::size_t n, std::uint8_t* length, std::uint8_t* length_below_top) {
  HWY_DYNAMIC_DISPATCH(BitLengths)(magnitude, n, length, length_below_top);
}

CleanupErrors cleanup_errors(const std::uint32_t* magnitude, const std::uint8_t* fraction, std::size_t n, int p,
                             double half_at_zero, bool refinement) {
  return HWY_DYNAMIC_DISPATCH(CleanupErrorSums)(magnitude, fraction, n, p, half_at_zero, refinement);
}

std::uint32_t quantize_row(const float* row, std::size_t n, float inverse_step, std::uint32_t* magnitude,
                           std::uint8_t* negative, std::uint8_t* fraction, std::uint8_t* length,
                           std::uint8_t* length_below_top, float* squares) {
  return HWY_DYNAMIC_DISPATCH(QuantizeRow)(row, n, inverse_step, magnitude, negative, fraction, length,
                                           length_below_top, squares);
}

void plane_errors(const std::uint32_t* magnitude, const std::uint8_t* fraction, std::size_t n, int planes,
                  double half_at_zero, int lowest_plane, double* error) {
  HWY_DYNAMIC_DISPATCH(PlaneErrors)(magnitude, fraction, n, planes, half_at_zero, lowest_plane, error);
}

}  // namespace codec::ht::simd
#endif
