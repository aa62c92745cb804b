#include "cleanup_encoder.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cstring>
#include <stdexcept>
#include <string>

#include "bit_packers.h"
#include "block_simd.h"
#include "vlc_encoding.h"
#include "simd_dispatch/scalar_clones.h"

namespace codec::ht {
namespace {

// Magnitude exponent E_n (T.814 7.3.7) of mu = magnitude >> p: the bit length of 2 mu - 1, 0 for an
// insignificant sample. v_n = 2 (mu - 1) + sign then fits in E_n bits, with bit E_n - 1 set
// whenever E_n > 1. From the magnitude's bit length L and T, that of the magnitude without its top
// bit: mu is significant when L > p, and a power of two (2 mu - 1 one bit shorter than 2 mu)
// exactly when no bit between p and the top is set, T <= p. Written without a branch, so that the
// row loop vectorises.
std::uint8_t exponent(std::uint8_t length, std::uint8_t below_top, std::uint8_t p) {
  const auto significant = static_cast<std::uint8_t>(length > p ? 1 : 0);
  return static_cast<std::uint8_t>(significant * (length - p + (below_top > p ? 1 : 0)));
}

// The block's magnitude exponents at the cleanup's plane as the cleanup pass sees them, with 0
// outside the block so that quads that straddle its right or bottom edge and the neighbours of
// edge quads need no special cases: they are kept with a border (two columns either side, a row
// above and below) wide enough for every neighbour the contexts and the exponent predictor read,
// so no read checks bounds. They come from the block's bit lengths (no shifted copy of the block
// is made per candidate plane) and live in a buffer of the thread's, reused from block to block.
class SampleGrid {
 public:
  SampleGrid(std::span<const std::uint8_t> lengths, std::span<const std::uint8_t> lengths_below_top, int width,
             int height, int plane)
      : width_(width),
        stride_(static_cast<std::size_t>(width) + 2 * kBorder),
        exponents_(thread_buffer<0>()),
        codes_(thread_buffer<1>()) {
    // Every cell is written, the borders and what follows the last row with 0, so the buffer
    // needs no clearing first (it held another block's cells, in another layout).
    const std::size_t rows_end = stride_ * (static_cast<std::size_t>(height) + 1);
    exponents_.resize(rows_end + stride_ + kRowOverread);
    cells_ = exponents_.data();
    std::memset(cells_, 0, stride_);
    for (int y = 0; y < height; ++y) {
      const std::uint8_t* length = lengths.data() + index(0, y);
      const std::uint8_t* below_top = lengths_below_top.data() + index(0, y);
      std::uint8_t* cells = cells_ + cell(0, y);
      const auto p = static_cast<std::uint8_t>(plane);
      std::memset(cells - kBorder, 0, kBorder);
      std::uint8_t bits = 0;  // the OR of the row's exponents
      for (int x = 0; x < width; ++x) {
        cells[x] = exponent(length[x], below_top[x], p);
        bits |= cells[x];
      }
      row_exponents_[static_cast<std::size_t>(y)] = bits;
      std::memset(cells + width, 0, kBorder);
    }
    std::memset(cells_ + rows_end, 0, stride_ + kRowOverread);
  }
  // The cell of (x, y), the cells of its row's next samples following it.
  const std::uint8_t* cells_at(int x, int y) const { return cells_ + cell(x, y); }
  std::uint8_t* cells_at(int x, int y) { return cells_ + cell(x, y); }

  // The adjustment codes (simd::adjustment_codes), laid out as the cells, made row by row as the
  // quad rows that may change need them (rows_with_codes).
  void prepare_adjustment_codes() {
    // Outside the block no sample may change: a quad on its right or bottom edge reads those
    // cells too (and a stale kRaise there would make a sample outside the block significant).
    codes_.assign(exponents_.size(), simd::kNoAdjustment);
    code_cells_ = codes_.data();
  }
  void rows_with_codes(std::span<const std::uint32_t> magnitudes, const CleanupAdjustment& adjustment, int y0, int y1,
                       int plane) {
    for (int y = y0; y < y1; ++y)
      simd::adjustment_codes(magnitudes.data() + index(0, y), adjustment.fractions.data() + index(0, y),
                             static_cast<std::size_t>(width_), plane, adjustment.raise_threshold,
                             code_cells_ + cell(0, y));
  }
  // Whether rows y0 .. y1 - 1 may change, as the grid was made: with raising, a significant sample
  // (an exponent of 1 or more); without, an exponent of 2 or more.
  bool may_adjust(int y0, int y1, bool raising) const {
    std::uint8_t any = 0;
    for (int y = y0; y < y1; ++y) any |= row_exponents_[static_cast<std::size_t>(y)];
    return (any & (raising ? 0xFF : 0xFE)) != 0;
  }
  const std::uint8_t* codes_at(int x, int y) const { return code_cells_ + cell(x, y); }

 private:
  template <int kWhich>
  static std::vector<std::uint8_t>& thread_buffer() {
    thread_local std::vector<std::uint8_t> buffer;
    return buffer;
  }
  static constexpr std::size_t kBorder = 2;
  // simd::quad_row_analysis reads whole vectors of cells past a row's last quad: the next rows',
  // or for the last row these bytes.
  static constexpr std::size_t kRowOverread = simd::kQuadRowOverread;
  std::size_t index(int x, int y) const {
    return static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) + static_cast<std::size_t>(x);
  }
  std::size_t cell(int x, int y) const {
    return static_cast<std::size_t>(y + 1) * stride_ + static_cast<std::size_t>(x + static_cast<int>(kBorder));
  }
  int width_;
  std::size_t stride_;
  std::vector<std::uint8_t>& exponents_;
  std::vector<std::uint8_t>& codes_;
  // Its cells, read through a plain pointer: GCC otherwise recomputes the thread_local vector's
  // address (a call to __tls_get_addr in a shared library) at reads in the quad loop.
  std::uint8_t* cells_ = nullptr;
  std::uint8_t* code_cells_ = nullptr;
  std::array<std::uint8_t, 1024> row_exponents_;  // per row (at most 1024): the OR of its exponents
};

// simd::quad_row_analysis writes each quad's index in VlcEncodingTable's layout.
static_assert(VlcEncodingTable::index(5, 9, true, 3) == (5u << 9 | 9u << 5 | 1u << 4 | 3u) &&
              VlcEncodingTable::index(7, 15, false, 0) == (7u << 9 | 15u << 5) &&
              VlcEncodingTable::rho_of(5u << 9 | 9u << 5) == 9 && VlcEncodingTable::context_of(5u << 9 | 9u << 5) == 5);

struct QuadCoding {
  int rho = 0;            // significance pattern
  int exponent_bits = 0;  // U_q: bits of each significant sample's v_n, before the EMB saving
  int residual = 0;       // u_q = U_q - kappa_q
  VlcCode code;           // the CxtVLC codeword, with its e_k pattern
};

// The unsigned residual u_q as U-VLC (T.814 7.3.6): a prefix of 1 to 3 bits, a suffix of 0, 1 or
// 5 bits and, for the largest values, a 4-bit extension; u = prefix value + suffix + 4 extension.
struct UvlcCode {
  std::uint32_t prefix = 0, suffix = 0, extension = 0;
  int prefix_bits = 0, suffix_bits = 0, extension_bits = 0;
};

UvlcCode uvlc(int u) {
  UvlcCode c;
  if (u == 1) {
    c.prefix = 1, c.prefix_bits = 1;  // "1"
  } else if (u == 2) {
    c.prefix = 2, c.prefix_bits = 2;  // "01", first bit first
  } else if (u <= 4) {
    c.prefix = 4, c.prefix_bits = 3;  // "001"
    c.suffix = static_cast<std::uint32_t>(u - 3), c.suffix_bits = 1;
  } else {
    c.prefix = 0, c.prefix_bits = 3;  // "000"
    const int d = u - 5;
    c.suffix_bits = 5;
    if (d < 28) {
      c.suffix = static_cast<std::uint32_t>(d);
    } else {
      c.suffix = static_cast<std::uint32_t>(28 + ((d - 28) & 3));
      c.extension = static_cast<std::uint32_t>((d - 28) >> 2), c.extension_bits = 4;
    }
  }
  return c;
}

// The residuals of one or two quads, in the order the decoder reads them: both prefixes, both
// suffixes, both extensions.
void put_residuals(VlcPacker& vlc, const UvlcCode* codes, int count) {
  for (int k = 0; k < count; ++k) vlc.put(codes[k].prefix, codes[k].prefix_bits);
  for (int k = 0; k < count; ++k) vlc.put(codes[k].suffix, codes[k].suffix_bits);
  for (int k = 0; k < count; ++k) vlc.put(codes[k].extension, codes[k].extension_bits);
}

void encode_pair_residuals(const QuadCoding* quads, int count, bool initial_row, MelEncoder& mel, VlcPacker& vlc) {
  std::array<UvlcCode, 2> codes{};
  int coded = 0;
  const bool both = count == 2 && quads[0].residual > 0 && quads[1].residual > 0;
  if (both && initial_row) {
    // T.814 7.3.6: in the first row a MEL symbol tells whether both residuals exceed 2; if so each
    // is sent less 2; if not and the first exceeds 2, the second (1 or 2) takes a single bit.
    const int u0 = quads[0].residual, u1 = quads[1].residual;
    const bool both_large = std::min(u0, u1) > 2;
    mel.encode(both_large);
    if (both_large) {
      codes[0] = uvlc(u0 - 2), codes[1] = uvlc(u1 - 2);
      put_residuals(vlc, codes.data(), 2);
    } else if (u0 > 2) {
      const UvlcCode first = uvlc(u0);
      vlc.put(first.prefix, first.prefix_bits);
      vlc.put(static_cast<std::uint32_t>(u1 - 1), 1);
      vlc.put(first.suffix, first.suffix_bits);
      vlc.put(first.extension, first.extension_bits);
    } else {
      codes[0] = uvlc(u0), codes[1] = uvlc(u1);
      put_residuals(vlc, codes.data(), 2);
    }
    return;
  }
  for (int k = 0; k < count; ++k)
    if (quads[k].residual > 0) codes[static_cast<std::size_t>(coded++)] = uvlc(quads[k].residual);
  put_residuals(vlc, codes.data(), coded);
}

// MagSgn bits of a quad (T.814 7.3.8): each significant sample sends the low U_q bits of v_n, or
// U_q - 1 where e_k implies the top one. They are gathered into one word and put at once while
// they fit (at most kWideBits). `values` holds the quad's four v_n (simd::quad_magsgn).
void put_magsgn(const std::uint32_t* values, const QuadCoding& q, MagSgnPacker& ms) {
  std::uint64_t word = 0;
  int count = 0;
  if (4 * q.exponent_bits <= MagSgnPacker::kWideBits) {
    // All four samples fit one word: each in turn, an insignificant one as 0 bits, without a branch
    // on the pattern (how many samples a quad has is as unpredictable as the data).
    for (int n = 0; n < 4; ++n) {
      const int bits = ((q.rho >> n) & 1) * (q.exponent_bits - ((q.code.e_k >> n) & 1));
      word |= (values[n] & ((std::uint64_t{1} << bits) - 1)) << count;
      count += bits;
    }
    ms.put_wide(word, count);
    return;
  }
  for (unsigned rho = static_cast<unsigned>(q.rho); rho != 0; rho &= rho - 1) {
    const int n = std::countr_zero(rho);
    const int bits = q.exponent_bits - ((q.code.e_k >> n) & 1);
    const std::uint64_t value = values[n] & ((std::uint64_t{1} << bits) - 1);
    if (count + bits > MagSgnPacker::kWideBits) {
      ms.put_wide(word, count);
      word = 0, count = 0;
    }
    word |= value << count;
    count += bits;
  }
  ms.put_wide(word, count);
}

// Joins MagSgn, MEL and VLC into Dcup (T.814 7.1): the MEL's and the VLC's last, partial bytes
// share one byte where their bits agree (and that byte is not 0xFF), and Scup = MEL + VLC bytes
// goes into the last byte and the low nibble of the one before it.
std::vector<std::uint8_t> assemble(const std::vector<std::uint8_t>& magsgn, MelPacker& mel, VlcPacker& vlc) {
  std::vector<std::uint8_t>& mel_bytes = mel.bytes();
  std::vector<std::uint8_t>& vlc_bytes = vlc.bytes();
  const bool mel_pending = mel.has_partial_byte(), vlc_pending = vlc.has_partial_byte();
  if (mel_pending && vlc_pending && !vlc.partial_is_scup_byte()) {
    const std::uint8_t mel_byte = mel.partial_byte(), vlc_byte = vlc.partial_byte();
    const std::uint8_t fused = mel_byte | vlc_byte;
    const bool agree = ((fused ^ mel_byte) & mel.partial_mask()) == 0 && ((fused ^ vlc_byte) & vlc.partial_mask()) == 0;
    if (agree && fused != 0xFF) {
      mel_bytes.push_back(fused);
    } else {
      mel_bytes.push_back(mel_byte);
      vlc_bytes.push_back(vlc_byte);
    }
  } else {
    if (mel_pending) mel_bytes.push_back(mel.partial_byte());
    if (vlc_pending) vlc_bytes.push_back(vlc.partial_byte());
  }
  const std::size_t scup = mel_bytes.size() + vlc_bytes.size();
  if (scup > 4079) throw std::logic_error("HT cleanup: MEL and VLC need " + std::to_string(scup) + " bytes, over 4079");
  // A new vector of the segment's size: the streams were given room for a typical block, and a
  // candidate keeps its codeword until rate control settles (thousands of them at once).
  std::vector<std::uint8_t> out;
  out.reserve(magsgn.size() + scup);
  out.insert(out.end(), magsgn.begin(), magsgn.end());
  out.insert(out.end(), mel_bytes.begin(), mel_bytes.end());
  out.insert(out.end(), vlc_bytes.rbegin(), vlc_bytes.rend());
  out[out.size() - 1] = static_cast<std::uint8_t>(scup >> 4);
  out[out.size() - 2] = static_cast<std::uint8_t>((out[out.size() - 2] & 0xF0) | (scup & 0x0F));
  return out;
}

// Scratch rows of the quad coder, each as wide as a row of quads (plus simd::kQuadRowOverwrite).
struct QuadRowBuffers {
  std::uint16_t* indices;
  std::uint16_t* exponents;
  std::uint16_t* patterns;       // adjustment only
  std::uint32_t* magsgn_values;  // 4 per quad
};

// The cleanup's rows of quads into its three streams. Built for x86-64-v3 as well
// (simd_dispatch/scalar_clones.h), everything inlined into it: on the 2048x2048 mosaic at
// 0.75 bpp (1 thread) 1,138 M to 1,126 M instructions, the same file.
[[gnu::flatten, GPUJ2K_X86_64_V3_CLONES]] void code_quad_rows(std::span<const std::uint32_t> magnitudes,
                                                              std::span<const std::uint8_t> negative, SampleGrid& grid,
                                                              int width, int height, int plane,
                                                              const CleanupAdjustment* adjustment,
                                                              const QuadRowBuffers& buffers, MagSgnPacker& magsgn,
                                                              MelEncoder& mel, VlcPacker& vlc) {
  const int quads_wide = (width + 1) / 2, quads_high = (height + 1) / 2;
  const auto w = static_cast<std::size_t>(width);
  std::uint16_t* const indices = buffers.indices;
  std::uint16_t* const exponents = buffers.exponents;
  std::uint16_t* const patterns = buffers.patterns;
  std::uint32_t* const magsgn_values = buffers.magsgn_values;
  for (int qy = 0; qy < quads_high; ++qy) {
    const bool initial_row = qy == 0;
    const VlcEncodingTable& table = vlc_encoding_table(initial_row ? QuadRowKind::Initial : QuadRowKind::Other);
    const int rows_end = std::min(2 * qy + 2, height);
    bool adjusts = adjustment && grid.may_adjust(2 * qy, rows_end, adjustment->raise_threshold != 0);
    if (adjusts) {
      grid.rows_with_codes(magnitudes, *adjustment, 2 * qy, rows_end, plane);
      adjusts =
          simd::adjust_quad_row(grid.cells_at(0, 2 * qy - 1), grid.cells_at(0, 2 * qy), grid.cells_at(0, 2 * qy + 1),
                                grid.codes_at(0, 2 * qy), grid.codes_at(0, 2 * qy + 1),
                                static_cast<std::size_t>(quads_wide), initial_row, patterns);
    }
    simd::quad_row_analysis(grid.cells_at(0, 2 * qy - 1), grid.cells_at(0, 2 * qy), grid.cells_at(0, 2 * qy + 1),
                            static_cast<std::size_t>(quads_wide), initial_row, indices, exponents);
    {
      const std::size_t upper = static_cast<std::size_t>(2 * qy) * w;
      const bool has_lower = 2 * qy + 1 < height;
      simd::quad_magsgn(magnitudes.data() + upper, has_lower ? magnitudes.data() + upper + w : nullptr,
                        negative.data() + upper, has_lower ? negative.data() + upper + w : nullptr, w, plane,
                        magsgn_values);
      // A lowered sample's index is one less, a raised one's 1 instead of 0: v = 2 (mu - 1) + sign
      // two less, or two more.
      for (int qx = 0; adjusts && qx < quads_wide; ++qx) {
        // Four quads at a time where none changed (most).
        std::uint64_t four;
        if (qx + 4 <= quads_wide && (std::memcpy(&four, patterns + qx, sizeof four), four == 0)) {
          qx += 3;
          continue;
        }
        for (unsigned bits = patterns[qx]; bits != 0; bits &= bits - 1) {
          const int b = std::countr_zero(bits), k = b & 3;
          const bool raised = b >= 4;
          std::uint32_t& value = magsgn_values[4 * static_cast<std::size_t>(qx) + static_cast<std::size_t>(k)];
          value = raised ? value + 2 : value - 2;
          (raised ? adjustment->raised : adjustment->lowered)
              ->push_back(upper + static_cast<std::size_t>(k & 1) * w + 2 * static_cast<std::size_t>(qx) +
                          static_cast<std::size_t>(k >> 1));
        }
      }
    }
    // Quads go in pairs (T.814 7.3.1): both quads' significance, then their residuals, then MagSgn.
    for (int qx = 0; qx < quads_wide; qx += 2) {
      // Runs of empty quads in context 0, four at a time: MEL 0s alone (most of a low-rate cleanup).
      int empty = 0;
      for (std::uint64_t four; qx + empty + 4 <= quads_wide; empty += 4) {
        std::memcpy(&four, indices + qx + empty, sizeof four);
        if (four != 0) break;
      }
      if (empty > 0) {
        mel.encode_zeros(empty);
        qx += empty;
        if (qx >= quads_wide) break;
      }
      const int count = std::min(2, quads_wide - qx);
      const std::uint16_t* index = indices + qx;
      if (((index[0] | (count == 2 ? index[1] : 0)) & VlcEncodingTable::kRhoBits) == 0) {
        // Neither quad has a significant sample: each sends its context's codeword for rho = 0, or
        // a MEL 0 in context 0, and no residual or MagSgn bit (most quads of a low-rate cleanup).
        for (int k = 0; k < count; ++k) {
          if (VlcEncodingTable::context_of(index[k]) == 0) {
            mel.encode(false);
          } else {
            const VlcCode& code = table.at(index[k]);
            vlc.put(code.codeword, code.length);
          }
        }
        continue;
      }
      std::array<QuadCoding, 2> quads;
      for (int k = 0; k < count; ++k) {
        QuadCoding& q = quads[static_cast<std::size_t>(k)];
        q.rho = VlcEncodingTable::rho_of(index[k]);
        q.exponent_bits = exponents[qx + k] & 0xFF;
        q.residual = exponents[qx + k] >> 8;
        // Context 0: the MEL says whether the quad has any significant sample (T.814 7.3.4).
        const bool in_context_zero = VlcEncodingTable::context_of(index[k]) == 0;
        if (in_context_zero) mel.encode(q.rho != 0);
        if (!in_context_zero || q.rho != 0) {
          q.code = table.at(index[k]);
          vlc.put(q.code.codeword, q.code.length);
        } else {
          q.code = VlcCode{};
        }
      }
      encode_pair_residuals(quads.data(), count, initial_row, mel, vlc);
      for (int k = 0; k < count; ++k)
        put_magsgn(magsgn_values + 4 * static_cast<std::size_t>(qx + k), quads[static_cast<std::size_t>(k)], magsgn);
    }
  }
}

}  // namespace

std::vector<std::uint8_t> encode_cleanup(std::span<const std::uint32_t> magnitudes,
                                         std::span<const std::uint8_t> negative, std::span<const std::uint8_t> lengths,
                                         std::span<const std::uint8_t> lengths_below_top, int width, int height,
                                         int plane, const CleanupAdjustment* adjustment) {
  if (width < 1 || height < 1 || width > 1024 || height > 1024 || width * height > 4096)
    throw std::invalid_argument("HT cleanup: a code-block of " + std::to_string(width) + "x" + std::to_string(height) +
                                " is outside 1..1024 with at most 4096 samples");
  const auto samples = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  if (magnitudes.size() != samples || negative.size() != samples || lengths.size() != samples ||
      lengths_below_top.size() != samples)
    throw std::invalid_argument("HT cleanup: magnitudes, signs and bit lengths must hold width * height samples");
  if (plane < 0 || plane > 30) throw std::invalid_argument("HT cleanup: the plane must be 0..30");
  if (adjustment &&
      (adjustment->fractions.size() != samples || plane > 23 || !adjustment->lowered || !adjustment->raised))
    throw std::invalid_argument("HT cleanup: adjusting needs a fraction per sample, a plane of at most 23 and lists");
  SampleGrid grid(lengths, lengths_below_top, width, height, plane);
  if (adjustment) grid.prepare_adjustment_codes();
  const int quads_wide = (width + 1) / 2;

  // Room for what a cleanup near a lossy cut usually takes (a 64x64 block's some hundreds of bytes
  // of MagSgn), so that the streams rarely reallocate as they grow.
  MagSgnPacker magsgn;
  magsgn.reserve(samples / 2);
  MelEncoder mel;
  mel.reserve(samples / 32);
  VlcPacker vlc;
  vlc.reserve(samples / 8);
  // Each row of quads is analysed at once (simd::quad_row_analysis); the loop below only emits.
  thread_local std::vector<std::uint16_t> index_buffer, exponent_buffer, pattern_buffer;
  thread_local std::vector<std::uint32_t> magsgn_buffer;
  magsgn_buffer.resize(4 * static_cast<std::size_t>(quads_wide));
  std::uint32_t* const magsgn_values = magsgn_buffer.data();
  index_buffer.resize(static_cast<std::size_t>(quads_wide) + simd::kQuadRowOverwrite);
  exponent_buffer.resize(static_cast<std::size_t>(quads_wide) + simd::kQuadRowOverwrite);
  std::uint16_t* const indices = index_buffer.data();
  std::uint16_t* const exponents = exponent_buffer.data();
  pattern_buffer.resize(adjustment ? static_cast<std::size_t>(quads_wide) + simd::kQuadRowOverwrite : 0);
  std::uint16_t* const patterns = pattern_buffer.data();
  code_quad_rows(magnitudes, negative, grid, width, height, plane, adjustment,
                 QuadRowBuffers{indices, exponents, patterns, magsgn_values}, magsgn, mel, vlc);
  std::vector<std::uint8_t> ms = magsgn.finish();
  return assemble(ms, mel.finish(), vlc);
}

}  // namespace codec::ht
