#include "refinement_encoder.h"

#include <algorithm>
#include <array>
#include <stdexcept>
#include <string>
#include <vector>

#include "bit_packers.h"
#include "block_simd.h"

namespace codec::ht {
namespace {

// The SigProp pass on plane q = p - 1 (T.814 7.4): stripes of four rows, each in groups of four
// columns; in a group, column by column and top to bottom, every sample not significant in the
// cleanup with a significant neighbour (in the cleanup, or made significant earlier in this pass:
// the scan is causal, so those are the ones already visited) sends bit q of its magnitude; then
// the group's newly significant samples send their signs (1: negative), in the same order.
//
// Within a stripe the scan is simply column by column, so the significance a sample's neighbours
// have when it is visited lives in one byte per column (`state`, with an empty column either side):
// bit 0 the row above the stripe (as the previous stripe left it, SigProp included), bits 1..4 the
// stripe's rows (the cleanup's significance, raised as the scan goes), bit 5 the row below (the
// cleanup's: not visited yet). A column none of whose samples has a neighbour is passed over with a
// few bit operations. `columns` holds simd::stripe_columns' bytes of every stripe, one after another.
void sigprop_pass(std::span<const std::uint32_t> m, std::span<const std::uint8_t> negative, int width, int height,
                  int q, std::span<const std::uint8_t> columns, SigPropPacker& out, std::vector<std::size_t>& became) {
  const auto w = static_cast<std::size_t>(width);
  // The thread's buffers, reused from block to block, reached through plain pointers in the loops
  // (each use of a thread_local in a shared library is a call to __tls_get_addr).
  thread_local std::vector<std::uint8_t> state_buffer, above_buffer;
  state_buffer.assign(w + 2, 0);
  above_buffer.assign(w, 0);
  std::uint8_t* const state = state_buffer.data();
  std::uint8_t* const above = above_buffer.data();
  // Samples made significant, written at every visit and kept where the bit is 1.
  thread_local std::vector<std::size_t> became_buffer;
  became_buffer.resize(w * static_cast<std::size_t>(height));
  std::size_t* const became_at = became_buffer.data();
  std::size_t became_count = 0;
  for (int y0 = 0; y0 < height; y0 += 4) {
    const int rows = std::min(4, height - y0);
    const std::uint8_t* stripe = columns.data() + static_cast<std::size_t>(y0 / 4) * w;
    for (std::size_t x = 0; x < w; ++x) state[x + 1] = static_cast<std::uint8_t>(above[x] | ((stripe[x] & 15) << 1));
    if (y0 + 4 < height) {
      const std::uint8_t* next = stripe + w;
      for (std::size_t x = 0; x < w; ++x) state[x + 1] = static_cast<std::uint8_t>(state[x + 1] | ((next[x] & 1) << 5));
    }
    const unsigned stripe_rows = (1u << rows) - 1;
    for (std::size_t x0 = 0; x0 < w; x0 += 4) {
      const std::size_t x1 = std::min(x0 + 4, w);
      // The group's bits (at most 16 of each kind), gathered and then put at once.
      std::uint32_t magnitude_bits = 0, sign_bits = 0;
      int magnitude_count = 0, sign_count = 0;
      for (std::size_t x = x0; x < x1; ++x) {
        unsigned column = state[x + 1];
        const unsigned sides = state[x] | state[x + 2];
        // Bit r: row r is insignificant and has a significant neighbour (rows r - 1 .. r + 1).
        const unsigned around = sides | column;
        if (((around | (around >> 1) | (around >> 2)) & ~(column >> 1) & stripe_rows) == 0) continue;
        // Row by row without a branch (whether a sample is visited, and what it sends, depends on
        // the data): a sample not visited sends nothing and changes nothing.
        std::size_t i = static_cast<std::size_t>(y0) * w + x;
        for (int r = 0; r < rows; ++r, i += w) {
          const unsigned visited = ((~column >> (r + 1)) & 1) & ((((sides | column) >> r) & 7) != 0 ? 1u : 0u);
          const unsigned bit = (m[i] >> q) & visited;
          magnitude_bits |= bit << magnitude_count;
          magnitude_count += static_cast<int>(visited);
          column |= bit << (r + 1);
          became_at[became_count] = i;
          became_count += bit;
          sign_bits |= ((negative[i] != 0 ? 1u : 0u) & bit) << sign_count;
          sign_count += static_cast<int>(bit);
        }
        state[x + 1] = static_cast<std::uint8_t>(column);
      }
      out.put(magnitude_bits, magnitude_count);
      out.put(sign_bits, sign_count);
    }
    for (std::size_t x = 0; x < w; ++x) above[x] = static_cast<std::uint8_t>((state[x + 1] >> 4) & 1);
  }
  became.assign(became_at, became_at + became_count);
}

// A stripe column's MagRef bits from simd::stripe_columns' byte: the bits of the significant rows,
// top row first (lowest), packed together (bits 0..3), and how many (bits 4..6).
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

// The MagRef pass on plane q = p - 1 (T.814 7.5): stripes of four rows, column by column, top to
// bottom, bit q of every sample significant in the cleanup (a magnitude at or above 2^p). Each
// column's bits come from its simd::stripe_columns byte and a table, and are packed 32 at a time.
void magref_pass(std::span<const std::uint8_t> columns, VlcPacker& out) {
  std::uint64_t bits = 0;
  int count = 0;
  for (const std::uint8_t column : columns) {
    const std::uint8_t entry = kColumnBits[column];
    bits |= static_cast<std::uint64_t>(entry & 15) << count;
    count += entry >> 4;
    if (count >= 32) {
      out.put(static_cast<std::uint32_t>(bits), 32);
      bits >>= 32;
      count -= 32;
    }
  }
  if (count > 0) out.put(static_cast<std::uint32_t>(bits), count);
}

}  // namespace

RefinementSegment encode_refinement(std::span<const std::uint32_t> magnitudes, std::span<const std::uint8_t> negative,
                                    int width, int height, int plane) {
  if (width < 1 || height < 1 || width > 1024 || height > 1024 || width * height > 4096)
    throw std::invalid_argument("HT refinement: a code-block of " + std::to_string(width) + "x" +
                                std::to_string(height) + " is outside 1..1024 with at most 4096 samples");
  const auto samples = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  if (magnitudes.size() != samples || negative.size() != samples)
    throw std::invalid_argument("HT refinement: magnitudes and signs must hold width * height samples");
  if (plane < 1 || plane > 31) throw std::invalid_argument("HT refinement: the cleanup plane must be 1..31");
  // Every stripe's columns: which samples the cleanup made significant, and their bit p - 1.
  const auto w = static_cast<std::size_t>(width);
  thread_local std::vector<std::uint8_t> column_buffer;
  column_buffer.resize(static_cast<std::size_t>((height + 3) / 4) * w);
  const std::span<std::uint8_t> columns(column_buffer);
  for (int y0 = 0; y0 < height; y0 += 4)
    simd::stripe_columns(magnitudes.data() + static_cast<std::size_t>(y0) * w, w, w, std::min(4, height - y0), plane,
                         columns.data() + static_cast<std::size_t>(y0 / 4) * w);
  RefinementSegment out;
  VlcPacker magref(VlcPacker::WithoutScup{});
  magref_pass(columns, magref);
  SigPropPacker sigprop;
  sigprop_pass(magnitudes, negative, width, height, plane - 1, columns, sigprop, out.became_significant);
  out.bytes = sigprop.finish();
  out.sigprop_bytes = out.bytes.size();
  const std::vector<std::uint8_t> backwards = magref.finish_without_scup();
  out.bytes.insert(out.bytes.end(), backwards.rbegin(), backwards.rend());
  return out;
}

}  // namespace codec::ht
