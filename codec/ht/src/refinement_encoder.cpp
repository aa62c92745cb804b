#include "refinement_encoder.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cstring>
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

// Which samples a pass has seen significant so far: those significant in the cleanup, and those
// the SigProp pass has made significant up to the current one. Kept with a border of insignificant
// samples around the block, so that a sample's eight neighbours are read without bounds checks.
class Significance {
 public:
  Significance(std::span<const std::uint32_t> magnitudes, int width, int height, int plane)
      : width_(width),
        stride_(static_cast<std::size_t>(width) + 2),
        state_(stride_ * (static_cast<std::size_t>(height) + 2) + kRowOverread, 0) {
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x) state_[cell(x, y)] = (magnitudes[index(x, y)] >> plane) != 0 ? 1 : 0;
  }
  // Whether any of the eight neighbours of the insignificant sample at `cell` is significant: the
  // three cells from its north-west, west and south-west neighbour each read as one word (the
  // sample's own cell is 0, so the middle word need not mask it).
  static bool any_neighbour(const std::uint8_t* cell, std::size_t stride) {
    std::uint32_t above, middle, below;
    std::memcpy(&above, cell - stride - 1, sizeof above);
    std::memcpy(&middle, cell - 1, sizeof middle);
    std::memcpy(&below, cell + stride - 1, sizeof below);
    return ((above | middle | below) & kThreeCells) != 0;
  }
  // Whether the cells around and in the `cols` x `rows` samples from (x0, y0) (cols, rows <= 4)
  // are all insignificant: then none of those samples has a significant neighbour. One word per
  // row, from the column left of x0.
  bool neighbourhood_empty(int x0, int y0, int cols, int rows) const {
    const int bytes = cols + 2;
    const std::uint64_t mask = std::endian::native == std::endian::little ? (std::uint64_t{1} << (8 * bytes)) - 1
                                                                          : ~std::uint64_t{0} << (64 - 8 * bytes);
    const std::uint8_t* row = state_.data() + cell(x0 - 1, y0 - 1);
    std::uint64_t any = 0;
    for (int r = 0; r < rows + 2; ++r, row += stride_) {
      std::uint64_t word;
      std::memcpy(&word, row, sizeof word);
      any |= word;
    }
    return (any & mask) == 0;
  }
  // Raw access for the passes' inner loops: the state byte of (x, y) is cells()[cell_of(x, y)],
  // rows stride() apart.
  std::uint8_t* cells() { return state_.data(); }
  const std::uint8_t* cells() const { return state_.data(); }
  std::size_t cell_of(int x, int y) const { return cell(x, y); }
  std::size_t stride() const { return stride_; }
  // The sample's index in the block's row-major arrays.
  std::size_t index(int x, int y) const {
    return static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) + static_cast<std::size_t>(x);
  }

 private:
  std::size_t cell(int x, int y) const {
    return (static_cast<std::size_t>(y) + 1) * stride_ + static_cast<std::size_t>(x) + 1;
  }

  // The low three bytes of a little-endian word: the three cells from the one it starts at.
  static constexpr std::uint32_t kThreeCells = std::endian::native == std::endian::little ? 0x00FFFFFFu : 0xFFFFFF00u;
  // neighbourhood_empty reads a 64-bit word from a bottom-border row's cell up to two left of
  // the last (any_neighbour a 32-bit one from the last): up to 6 cells past the buffer's end.
  static constexpr std::size_t kRowOverread = 8;
  int width_;
  std::size_t stride_;
  std::vector<std::uint8_t> state_;  // 0 insignificant, 1 significant in the cleanup, 2 by SigProp
};

// The SigProp pass on plane q = p - 1 (T.814 7.4): stripes of four rows, each in groups of four
// columns; in a group, column by column and top to bottom, every sample not significant in the
// cleanup with a significant neighbour (in the cleanup, or made significant earlier in this pass:
// the scan is causal, so those are the ones already visited) sends bit q of its magnitude; then
// the group's newly significant samples send their signs (1: negative), in the same order.
void sigprop_pass(std::span<const std::uint32_t> m, std::span<const std::uint8_t> negative, int width, int height,
                  int q, Significance& sig, SigPropPacker& out, std::vector<std::size_t>& became) {
  for (int y0 = 0; y0 < height; y0 += 4) {
    const int y1 = std::min(y0 + 4, height);
    for (int x0 = 0; x0 < width; x0 += 4) {
      const int x1 = std::min(x0 + 4, width);
      // Most groups of a sparse plane have no significant sample near them: nothing to send.
      if (sig.neighbourhood_empty(x0, y0, x1 - x0, y1 - y0)) continue;
      const std::size_t group_start = became.size();
      const std::size_t stride = sig.stride();
      for (int x = x0; x < x1; ++x) {
        std::uint8_t* cell = sig.cells() + sig.cell_of(x, y0);
        std::size_t i = sig.index(x, y0);
        for (int y = y0; y < y1; ++y, cell += stride, i += static_cast<std::size_t>(width)) {
          if (cell[0] != 0 || !Significance::any_neighbour(cell, stride)) continue;
          const std::uint32_t bit = (m[i] >> q) & 1;
          out.put(bit, 1);
          if (bit) {
            cell[0] = 2;  // significant by SigProp
            became.push_back(i);
          }
        }
      }
      for (std::size_t k = group_start; k < became.size(); ++k) out.put(negative[became[k]] ? 1 : 0, 1);
    }
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
// column's bits come from one byte of simd::stripe_columns and a table, and are packed 32 at a time.
void magref_pass(std::span<const std::uint32_t> m, int width, int height, int p, MagRefPacker& out) {
  const auto w = static_cast<std::size_t>(width);
  thread_local std::vector<std::uint8_t> columns;
  columns.resize(w);
  std::uint64_t bits = 0;
  int count = 0;
  for (int y0 = 0; y0 < height; y0 += 4) {
    simd::stripe_columns(m.data() + static_cast<std::size_t>(y0) * w, w, w, std::min(4, height - y0), p,
                         columns.data());
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
  Significance sig(magnitudes, width, height, plane);
  RefinementSegment out;
  MagRefPacker magref;
  magref_pass(magnitudes, width, height, plane, magref);
  SigPropPacker sigprop;
  sigprop_pass(magnitudes, negative, width, height, plane - 1, sig, sigprop, out.became_significant);
  out.bytes = sigprop.finish();
  out.sigprop_bytes = out.bytes.size();
  const std::vector<std::uint8_t> backwards = magref.finish();
  out.bytes.insert(out.bytes.end(), backwards.rbegin(), backwards.rend());
  return out;
}

}  // namespace codec::ht
