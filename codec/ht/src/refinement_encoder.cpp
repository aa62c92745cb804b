#include "refinement_encoder.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#if defined(__GNUC__) && defined(__x86_64__)
#include <immintrin.h>
#endif

#include "bit_packers.h"
#include "block_simd.h"

namespace codec::ht {
namespace {

// A stripe column's bits where a 4-bit row mask (bits 0..3 of the index) is set, taken from bits
// 4..7 of the index: packed together, top row first (bits 0..3), and how many (bits 4..6). MagRef
// indexes it with simd::stripe_columns' byte, SigProp with a group column's visited rows and bits.
constexpr std::array<std::uint8_t, 256> kColumnBits = [] {
  std::array<std::uint8_t, 256> out{};
  for (unsigned code = 0; code < 256; ++code) {
    const unsigned significant = code & 15, bits = code >> 4;
    unsigned packed = 0, count = 0;
    for (unsigned r = 0; r < 4; ++r)
      if ((significant >> r) & 1) packed |= ((bits >> r) & 1) << count++;
    out[code] = static_cast<std::uint8_t>(packed | (count << 4));
  }
  return out;
}();

// Bit c of a nibble moved to bit 4c: a group's row of four columns in the column-major order of
// its 16 samples (bit 4c + r: column c, row r).
constexpr std::array<std::uint16_t, 16> kSpreadNibble = [] {
  std::array<std::uint16_t, 16> out{};
  for (unsigned n = 0; n < 16; ++n)
    for (unsigned c = 0; c < 4; ++c) out[n] = static_cast<std::uint16_t>(out[n] | (((n >> c) & 1u) << (4 * c)));
  return out;
}();

// The 16 samples of the group of four columns from bit x of four row masks, in scan order.
std::uint32_t group_bits(const std::uint64_t* rows, unsigned x) {
  std::uint32_t out = 0;
  for (unsigned r = 0; r < 4; ++r) out |= static_cast<std::uint32_t>(kSpreadNibble[(rows[r] >> x) & 15]) << r;
  return out;
}

// The SigProp pass on plane q = p - 1 (T.814 7.4): stripes of four rows, each in groups of four
// columns; in a group, column by column and top to bottom, every sample not significant in the
// cleanup with a significant neighbour (in the cleanup, or made significant earlier in this pass:
// the scan is causal, so those are the ones already visited) sends bit q of its magnitude; then
// the group's newly significant samples send their signs (1: negative), in the same order.
//
// A stripe is worked out 64 columns at a time on row masks (simd::column_bit_masks of the
// stripe_columns bytes), not sample by sample. What the cleanup made significant is known
// everywhere, so the samples that neighbour it are found at once. A sample made significant in
// this pass reaches only samples visited after it: the one below it and the three in the next
// column. Those are added and the new significance recomputed until nothing changes; since every
// influence points forwards in the scan, that fixed point is the scan's outcome. The groups then
// send their bits in scan order.
void sigprop_pass(std::span<const std::uint8_t> negative, int width, int height, std::span<const std::uint8_t> columns,
                  SigPropPacker& out, std::vector<std::size_t>& became) {
  const auto w = static_cast<std::size_t>(width);
  const std::size_t words = (w + 63) / 64;
  const std::size_t stripes = (static_cast<std::size_t>(height) + 3) / 4;
  // Per stripe, its column bytes' 8 bits as row masks (significance of rows 0..3, then their bit q),
  // every stripe's one after another, with the 8 spare bytes column_bit_masks asks for. The thread's
  // buffers, reused from block to block, are reached through plain pointers in the loops (each use
  // of a thread_local in a shared library is a call to __tls_get_addr).
  thread_local std::vector<std::uint64_t> mask_buffer, state_buffer;
  mask_buffer.resize(stripes * 8 * words + 1);
  std::uint64_t* const masks = mask_buffer.data();
  for (std::size_t s = 0; s < stripes; ++s)
    simd::column_bit_masks(columns.data() + s * w, w, words, masks + s * 8 * words);
  // Per word: the row above the stripe as it ends up (the previous stripe's last row, SigProp
  // included), and the stripe's newly significant samples (E) and visited samples (V) per row.
  state_buffer.assign(9 * words, 0);
  std::uint64_t* const above = state_buffer.data();
  std::uint64_t* const became_rows = above + words;
  std::uint64_t* const visited_rows = became_rows + 4 * words;
  thread_local std::vector<std::size_t> became_buffer;
  became_buffer.resize(w * static_cast<std::size_t>(height));
  std::size_t* const became_at = became_buffer.data();
  std::size_t became_count = 0;
  const std::uint64_t last_word_columns = w % 64 == 0 ? ~std::uint64_t{0} : (std::uint64_t{1} << (w % 64)) - 1;
  for (std::size_t s = 0; s < stripes; ++s) {
    const std::uint64_t* const significant = masks + s * 8 * words;  // rows 0..3, `words` apart
    const std::uint64_t* const bits = significant + 4 * words;
    // The cleanup's significance of the row below the stripe (none below the last).
    const std::uint64_t* const below = s + 1 < stripes ? masks + (s + 1) * 8 * words : nullptr;
    const int rows = std::min(4, height - static_cast<int>(4 * s));
    auto row_word = [&](const std::uint64_t* m, int r, std::size_t k) -> std::uint64_t {
      if (r < 0) return above[k];
      if (r >= 4) return below ? below[k] : 0;
      return m[static_cast<std::size_t>(r) * words + k];
    };
    std::uint64_t carry = 0;  // newly significant samples of the previous word's last column, rows 0..3
    for (std::size_t k = 0; k < words; ++k) {
      const std::uint64_t columns_here = k + 1 == words ? last_word_columns : ~std::uint64_t{0};
      // Per row: samples with a neighbour the cleanup made significant (or the row above, final),
      // and not significant themselves; the rows past the block's last have no samples.
      std::uint64_t candidates[4], insignificant[4], bit[4], e[4];
      for (int r = 0; r < 4; ++r) {
        std::uint64_t left = 0, right = 0, middle = 0;
        for (int n = r - 1; n <= r + 1; ++n) {
          const std::uint64_t m = row_word(significant, n, k);
          middle |= m;
          left |= k > 0 ? row_word(significant, n, k - 1) >> 63 : 0;
          right |= k + 1 < words ? row_word(significant, n, k + 1) << 63 : 0;
        }
        const std::uint64_t around = middle | (middle << 1) | left | (middle >> 1) | right;
        insignificant[r] = r < rows ? ~significant[static_cast<std::size_t>(r) * words + k] & columns_here : 0;
        candidates[r] = around & insignificant[r];
        bit[r] = bits[static_cast<std::size_t>(r) * words + k];
        e[r] = candidates[r] & bit[r];
      }
      // Newly significant samples reach the sample below and the next column's three.
      std::uint64_t v[4];
      for (;;) {
        bool changed = false;
        for (int r = 0; r < 4; ++r) {
          const std::uint64_t up = r > 0 ? e[r - 1] : 0, down = r < 3 ? e[r + 1] : 0;
          const std::uint64_t carried = ((carry >> r) | (r > 0 ? carry >> (r - 1) : 0) | (carry >> (r + 1))) & 1;
          const std::uint64_t reached = up | ((up | e[r] | down) << 1) | carried;
          v[r] = candidates[r] | (reached & insignificant[r]);
          const std::uint64_t now = v[r] & bit[r];
          changed |= now != e[r];
          e[r] = now;
        }
        if (!changed) break;
      }
      carry = 0;
      for (int r = 0; r < 4; ++r) {
        carry |= (e[r] >> 63) << r;
        became_rows[static_cast<std::size_t>(r) * words + k] = e[r];
        visited_rows[static_cast<std::size_t>(r) * words + k] = v[r];
      }
    }
    // The groups' bits in scan order (a group lies within one word: 64 is a multiple of 4).
    for (std::size_t x0 = 0; x0 < w; x0 += 4) {
      const std::size_t k = x0 / 64;
      const auto shift = static_cast<unsigned>(x0 % 64);
      const std::uint64_t rows_v[4] = {visited_rows[k], visited_rows[words + k], visited_rows[2 * words + k],
                                       visited_rows[3 * words + k]};
      if ((((rows_v[0] | rows_v[1] | rows_v[2] | rows_v[3]) >> shift) & 15) == 0) continue;
      const std::uint32_t visit = group_bits(rows_v, shift);
      const std::uint64_t rows_b[4] = {bits[k], bits[words + k], bits[2 * words + k], bits[3 * words + k]};
      const std::uint32_t value = group_bits(rows_b, shift) & visit;
      std::uint32_t magnitude_bits = 0, sign_bits = 0;
      int magnitude_count = 0, sign_count = 0;
      for (unsigned c = 0; c < 4; ++c) {
        const std::uint8_t entry = kColumnBits[((visit >> (4 * c)) & 15) | (((value >> (4 * c)) & 15) << 4)];
        magnitude_bits |= static_cast<std::uint32_t>(entry & 15) << magnitude_count;
        magnitude_count += entry >> 4;
      }
      for (std::uint32_t left = value; left != 0; left &= left - 1) {
        const int j = std::countr_zero(left);
        const std::size_t i = (4 * s + static_cast<std::size_t>(j & 3)) * w + x0 + static_cast<std::size_t>(j >> 2);
        sign_bits |= (negative[i] != 0 ? 1u : 0u) << sign_count++;
        became_at[became_count++] = i;
      }
      out.put(magnitude_bits, magnitude_count);
      out.put(sign_bits, sign_count);
    }
    // The next stripe's row above: this stripe's last row, as it ends.
    for (std::size_t k = 0; k < words; ++k)
      above[k] = rows == 4 ? significant[3 * words + k] | became_rows[3 * words + k] : 0;
  }
  became.assign(became_at, became_at + became_count);
}

// The MagRef pass' bits gathered into words and put 32 at a time.
class MagRefBits {
 public:
  explicit MagRefBits(VlcPacker& out) : out_(out) {}
  // `count` more bits (at most 32), `packed` holding them lowest first and nothing above.
  void add(std::uint64_t packed, int count) {
    bits_ |= packed << count_;
    count_ += count;
    if (count_ >= 32) {
      out_.put(static_cast<std::uint32_t>(bits_), 32);
      bits_ >>= 32;
      count_ -= 32;
    }
  }
  void finish() {
    if (count_ > 0) out_.put(static_cast<std::uint32_t>(bits_), count_);
  }

 private:
  VlcPacker& out_;
  std::uint64_t bits_ = 0;  // pending, fewer than 32
  int count_ = 0;
};

// The MagRef pass on plane q = p - 1 (T.814 7.5): stripes of four rows, column by column, top to
// bottom, bit q of every sample significant in the cleanup (a magnitude at or above 2^p). Each
// column's bits come from its simd::stripe_columns byte and a table.
void magref_columns(std::span<const std::uint8_t> columns, MagRefBits& bits) {
  for (const std::uint8_t column : columns) {
    const std::uint8_t entry = kColumnBits[column];
    bits.add(entry & 15, entry >> 4);
  }
}

void magref_pass(std::span<const std::uint8_t> columns, VlcPacker& out) {
  MagRefBits bits(out);
  magref_columns(columns, bits);
  bits.finish();
}

#if defined(__GNUC__) && defined(__x86_64__)
// The same eight columns at a time with BMI2's PEXT, which gathers the bits of eight column bytes'
// high nibbles where their low nibbles are set, in column order: one instruction for what the
// table takes eight lookups.
[[gnu::target("bmi2,popcnt")]] void magref_pass_bmi2(std::span<const std::uint8_t> columns, VlcPacker& out) {
  constexpr std::uint64_t kLowNibbles = 0x0F0F0F0F0F0F0F0Full;
  MagRefBits bits(out);
  std::size_t i = 0;
  for (; i + 8 <= columns.size(); i += 8) {
    std::uint64_t eight;
    std::memcpy(&eight, columns.data() + i, sizeof eight);
    const std::uint64_t significant = eight & kLowNibbles;
    bits.add(_pext_u64((eight >> 4) & kLowNibbles, significant), static_cast<int>(_mm_popcnt_u64(significant)));
  }
  magref_columns(columns.subspan(i), bits);
  bits.finish();
}

// PEXT where it is fast: not on AMD's family 17h (Zen, Zen 2), which runs it in microcode, some
// 8 cycles a set mask bit.
bool fast_bit_extract() {
  static const bool fast = __builtin_cpu_supports("bmi2") && !__builtin_cpu_is("amdfam17h");
  return fast;
}
#endif

void code_magref(std::span<const std::uint8_t> columns, VlcPacker& out) {
#if defined(__GNUC__) && defined(__x86_64__)
  if (fast_bit_extract()) return magref_pass_bmi2(columns, out);
#endif
  magref_pass(columns, out);
}

}  // namespace

RefinementSegment encode_refinement(std::span<const std::uint32_t> magnitudes, std::span<const std::uint8_t> negative,
                                    int width, int height, int plane, const SigPropRaise& raise,
                                    std::span<const std::size_t> lowered) {
  if (width < 1 || height < 1 || width > 1024 || height > 1024 || width * height > 4096)
    throw std::invalid_argument("HT refinement: a code-block of " + std::to_string(width) + "x" +
                                std::to_string(height) + " is outside 1..1024 with at most 4096 samples");
  const auto samples = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  if (magnitudes.size() != samples || negative.size() != samples)
    throw std::invalid_argument("HT refinement: magnitudes and signs must hold width * height samples");
  if (plane < 1 || plane > 31) throw std::invalid_argument("HT refinement: the cleanup plane must be 1..31");
  const bool raising = !raise.fractions.empty();
  if (raising && (raise.fractions.size() != samples || plane > 15 || raise.threshold < 0 ||
                  raise.threshold > (std::int32_t{1} << (plane - 1 + 8))))
    throw std::invalid_argument(
        "HT refinement: SigProp raising needs a fraction per sample, a plane of at most 15 "
        "and a threshold within the plane");
  // Every stripe's columns: which samples the cleanup made significant, and their bit p - 1.
  const auto w = static_cast<std::size_t>(width);
  thread_local std::vector<std::uint8_t> column_buffer;
  column_buffer.resize(static_cast<std::size_t>((height + 3) / 4) * w);
  const std::span<std::uint8_t> columns(column_buffer);
  for (int y0 = 0; y0 < height; y0 += 4)
    simd::stripe_columns(magnitudes.data() + static_cast<std::size_t>(y0) * w,
                         raising ? raise.fractions.data() + static_cast<std::size_t>(y0) * w : nullptr, w, w,
                         std::min(4, height - y0), plane, raise.threshold,
                         columns.data() + static_cast<std::size_t>(y0 / 4) * w);
  for (const std::size_t i : lowered) {
    if (i >= samples) throw std::invalid_argument("HT refinement: a lowered sample outside the block");
    const std::size_t y = i / w;
    columns[y / 4 * w + i % w] |= static_cast<std::uint8_t>(1u << (4 + y % 4));
  }
  RefinementSegment out;
  VlcPacker magref(VlcPacker::WithoutScup{});
  magref.reserve(samples / 8);
  code_magref(columns, magref);
  SigPropPacker sigprop;
  sigprop.reserve(samples / 8);
  sigprop_pass(negative, width, height, columns, sigprop, out.became_significant);
  out.bytes = sigprop.finish();
  out.sigprop_bytes = out.bytes.size();
  const std::vector<std::uint8_t> backwards = magref.finish_without_scup();
  out.bytes.insert(out.bytes.end(), backwards.rbegin(), backwards.rend());
  return out;
}

}  // namespace codec::ht
