#include "refinement_encoder.h"

#include <algorithm>
#include <array>
#include <stdexcept>
#include <string>
#include <vector>

#include "block_simd.h"

namespace codec::ht {
namespace {

// SigProp bits (T.814 7.1.5): forwards, least significant bit first; a byte after 0xFF carries
// only 7 bits (its most significant bit a stuffed 0), as in MagSgn. A decoder reads 0s past the
// bits it needs, so the last byte is padded with 0s.
class SigPropPacker {
 public:
  // The low `count` bits of `bits` (count <= 32, no bit set above them), least significant first.
  void put(std::uint32_t bits, int count) {
    acc_ |= static_cast<std::uint64_t>(bits) << used_;
    used_ += count;
    while (used_ >= capacity_) {
      const auto byte = static_cast<std::uint8_t>(acc_ & ((1u << capacity_) - 1));
      bytes_.push_back(byte);
      acc_ >>= capacity_;
      used_ -= capacity_;
      capacity_ = byte == 0xFF ? 7 : 8;
    }
  }
  // A last 0xFF is followed by a 0 byte (a stuffed byte of padding): the MagRef bytes that follow
  // in the segment, or the next packet's, must not form a marker with it.
  std::vector<std::uint8_t> finish() {
    if (used_ > 0) bytes_.push_back(static_cast<std::uint8_t>(acc_));
    if (!bytes_.empty() && bytes_.back() == 0xFF) bytes_.push_back(0x00);
    return std::move(bytes_);
  }

 private:
  std::vector<std::uint8_t> bytes_;
  std::uint64_t acc_ = 0;  // bits not yet in a byte, the next one lowest
  int used_ = 0, capacity_ = 8;
};

// MagRef bits (T.814 7.1.6): least significant bit first into bytes laid out backwards from the
// segment's end, with the VLC's stuffing rule: a byte after one above 0x8F whose low 7 bits are
// all 1 carries a stuffed 0 in bit 7 (and so only 7 bits). The decoder starts as if a byte above
// 0x8F preceded the first, so the segment never ends in 0xFF. Past the end it reads 0s: the last
// byte is 0-padded.
class MagRefPacker {
 public:
  // As SigPropPacker::put.
  void put(std::uint32_t bits, int count) {
    acc_ |= static_cast<std::uint64_t>(bits) << used_;
    used_ += count;
    while (used_ >= 8) {
      auto byte = static_cast<std::uint32_t>(acc_ & 0xFF);
      const int taken = last_ > 0x8F && (byte & 0x7F) == 0x7F ? 7 : 8;
      byte &= (1u << taken) - 1;
      bytes_.push_back(static_cast<std::uint8_t>(byte));
      last_ = byte;
      acc_ >>= taken;
      used_ -= taken;
    }
  }
  // Bytes in the order written (the segment's last byte first). Seven pending bits that would be
  // stuffed give the same byte as the stuffing would (0x7F).
  std::vector<std::uint8_t> finish() {
    if (used_ > 0) bytes_.push_back(static_cast<std::uint8_t>(acc_));
    return std::move(bytes_);
  }

 private:
  std::vector<std::uint8_t> bytes_;
  std::uint64_t acc_ = 0;
  int used_ = 0;
  std::uint32_t last_ = 0xFF;
};

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
      const std::size_t group_start = became.size();
      for (std::size_t x = x0; x < x1; ++x) {
        unsigned column = state[x + 1];
        const unsigned sides = state[x] | state[x + 2];
        // Bit r: row r is insignificant and has a significant neighbour (rows r - 1 .. r + 1).
        const unsigned around = sides | column;
        if (((around | (around >> 1) | (around >> 2)) & ~(column >> 1) & stripe_rows) == 0) continue;
        std::size_t i = static_cast<std::size_t>(y0) * w + x;
        for (int r = 0; r < rows; ++r, i += w) {
          if ((column >> (r + 1)) & 1) continue;
          if ((((sides | column) >> r) & 7) == 0) continue;
          const std::uint32_t bit = (m[i] >> q) & 1;
          out.put(bit, 1);
          if (bit) {
            column |= 1u << (r + 1);
            became.push_back(i);
          }
        }
        state[x + 1] = static_cast<std::uint8_t>(column);
      }
      for (std::size_t k = group_start; k < became.size(); ++k) out.put(negative[became[k]] ? 1 : 0, 1);
    }
    for (std::size_t x = 0; x < w; ++x) above[x] = static_cast<std::uint8_t>((state[x + 1] >> 4) & 1);
  }
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
void magref_pass(std::span<const std::uint8_t> columns, MagRefPacker& out) {
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
  MagRefPacker magref;
  magref_pass(columns, magref);
  SigPropPacker sigprop;
  sigprop_pass(magnitudes, negative, width, height, plane - 1, columns, sigprop, out.became_significant);
  out.bytes = sigprop.finish();
  out.sigprop_bytes = out.bytes.size();
  const std::vector<std::uint8_t> backwards = magref.finish();
  out.bytes.insert(out.bytes.end(), backwards.rbegin(), backwards.rend());
  return out;
}

}  // namespace codec::ht
