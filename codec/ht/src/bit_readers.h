#pragma once
#include <algorithm>
#include <bit>
#include <cstddef>
#include <cstring>
#include <cstdint>
#include <span>

// The decoder's side of bit_packers.h: the three bit-streams of an HT cleanup segment (T.814 7.1)
// read back with their stuffing removed. Each reader owns nothing, never reads outside its part of
// the segment, and returns fill bits past its end (what the encoder's padding assumes), so a
// malformed segment decodes to garbage samples, never to an out-of-bounds read.

namespace codec::ht {

// The index (0..7, least significant first) of the lowest zero byte of `word`, 8 for none. The
// classic test marks the lowest zero byte exactly (a borrow can only mark bytes above it); the
// bulk refills below use it to find the first byte that stuffing may affect.
inline int lowest_zero_byte(std::uint64_t word) {
  const std::uint64_t marks = (word - 0x0101010101010101u) & ~word & 0x8080808080808080u;
  return marks == 0 ? 8 : std::countr_zero(marks) / 8;
}

// MagSgn (T.814 7.1.2): bytes forwards from the segment's start, bits least significant first; a
// byte that follows 0xFF carries 7 bits (its most significant bit is a stuffed 0). Past the end it
// reads 0xFF bytes, as the encoder's finish() assumes.
class MagSgnReader {
 public:
  explicit MagSgnReader(std::span<const std::uint8_t> bytes) : bytes_(bytes) {}
  // The next `count` bits (count <= 32), the first read in bit 0.
  std::uint32_t get(int count) {
    ensure(count);
    return take(count);
  }
  // Makes the next `count` bits (count <= 56) available to take() without further reads.
  void ensure(int count) {
    while (available_ < count) refill();
  }
  // The next `count` bits (count <= 32) of those ensure() made available.
  std::uint32_t take(int count) {
    const std::uint64_t mask = (std::uint64_t{1} << count) - 1;
    const auto value = static_cast<std::uint32_t>(acc_ & mask);
    acc_ >>= count;
    available_ -= count;
    return value;
  }

 private:
  void refill() {
    if constexpr (std::endian::native == std::endian::little) {
      // Whole bytes at once while none of them follows a 0xFF: up to the first 0xFF (which itself
      // carries 8 bits), as many as the accumulator has room for (a lossless block reads some
      // 10 bits per sample, a byte at a time one refill per byte).
      if (!last_was_ff_ && pos_ + 8 <= bytes_.size()) {
        std::uint64_t word;
        std::memcpy(&word, bytes_.data() + pos_, sizeof word);
        const int first_ff = lowest_zero_byte(~word);  // a 0xFF byte is a zero byte of ~word
        const int room = (64 - available_) / 8;
        const int take = std::min(room, first_ff + 1);
        if (take > 0) {
          const std::uint64_t taken = take == 8 ? word : word & ((std::uint64_t{1} << (8 * take)) - 1);
          acc_ |= taken << available_;
          available_ += 8 * take;
          pos_ += static_cast<std::size_t>(take);
          last_was_ff_ = take == first_ff + 1;
          return;
        }
      }
    }
    const std::uint8_t byte = pos_ < bytes_.size() ? bytes_[pos_] : 0xFF;
    ++pos_;
    const int bits = last_was_ff_ ? 7 : 8;
    acc_ |= static_cast<std::uint64_t>(byte & ((1u << bits) - 1)) << available_;
    available_ += bits;
    last_was_ff_ = byte == 0xFF;
  }
  std::span<const std::uint8_t> bytes_;
  std::size_t pos_ = 0;
  std::uint64_t acc_ = 0;
  int available_ = 0;
  bool last_was_ff_ = false;
};

// The MEL bit-stream (T.814 7.1.3): bytes forwards from the start of the MEL/VLC suffix, bits most
// significant first, 7 bits after 0xFF. Past the end it reads 1s (a run the decoder never uses).
class MelBitReader {
 public:
  explicit MelBitReader(std::span<const std::uint8_t> bytes) : bytes_(bytes) {}
  int bit() {
    if (remaining_ == 0) {
      const std::uint8_t next = pos_ < bytes_.size() ? bytes_[pos_] : 0xFF;
      ++pos_;
      remaining_ = byte_ == 0xFF ? 7 : 8;
      byte_ = next;
    }
    --remaining_;
    return (byte_ >> remaining_) & 1;
  }

 private:
  std::span<const std::uint8_t> bytes_;
  std::size_t pos_ = 0;
  std::uint8_t byte_ = 0;
  int remaining_ = 0;
};

// The MEL decoder (T.814 7.3.3): the adaptive run-length code of MelEncoder read back. A 1 bit is a
// full run of 2^E[k] zero symbols (k rises); a 0 bit is followed by E[k] bits giving a shorter run
// of zeros that ends with a 1 symbol (k falls).
class MelDecoder {
 public:
  explicit MelDecoder(std::span<const std::uint8_t> bytes) : bits_(bytes) {}
  bool decode() {
    while (zeros_ == 0 && !one_pending_) {
      const int exponent = kExponent[state_];
      if (bits_.bit()) {
        zeros_ = 1 << exponent;
        if (state_ < 12) ++state_;
      } else {
        int run = 0;
        for (int i = 0; i < exponent; ++i) run = (run << 1) | bits_.bit();
        zeros_ = run;
        one_pending_ = true;
        if (state_ > 0) --state_;
      }
    }
    if (zeros_ > 0) {
      --zeros_;
      return false;
    }
    one_pending_ = false;
    return true;
  }

 private:
  // T.814 Table 2 (the MEL exponent table E[k], k = 0..12), as MelEncoder uses it.
  static constexpr int kExponent[13] = {0, 0, 0, 1, 1, 1, 2, 2, 2, 3, 3, 4, 5};
  MelBitReader bits_;
  int state_ = 0, zeros_ = 0;
  bool one_pending_ = false;
};

// The VLC bit-stream (T.814 7.1.4): bytes backwards from the segment's second last byte, bits least
// significant first. That byte gives only its high nibble (its low one and the last byte hold Scup);
// for stuffing the decoder sees it with the nibble as 1s and a 0xFF before it, as VlcPacker writes
// it. A byte after one above 0x8F whose low 7 bits are all 1 carries 7 bits. Past the start of the
// MEL/VLC suffix it reads 0s.
class VlcReader {
 public:
  // `suffix`: the segment's last Scup bytes (MEL forwards, VLC backwards), at least 2.
  explicit VlcReader(std::span<const std::uint8_t> suffix) : bytes_(suffix), pos_(suffix.size() - 2) {
    const std::uint32_t first = static_cast<std::uint32_t>(bytes_[pos_]) | 0x0F;
    const int bits = (first & 0x7F) == 0x7F ? 3 : 4;  // after the virtual 0xFF, bit 7 may be stuffed
    acc_ = (first >> 4) & ((1u << bits) - 1);
    available_ = bits;
    last_ = first;
  }
  std::uint32_t peek7() {
    while (available_ < 7) refill();
    return static_cast<std::uint32_t>(acc_ & 0x7F);
  }
  void skip(int count) {
    while (available_ < count) refill();
    acc_ >>= count;
    available_ -= count;
  }
  std::uint32_t get(int count) {
    while (available_ < count) refill();
    const auto value = static_cast<std::uint32_t>(acc_ & ((std::uint64_t{1} << count) - 1));
    acc_ >>= count;
    available_ -= count;
    return value;
  }

 private:
  void refill() {
    if constexpr (std::endian::native == std::endian::little) {
      // Whole bytes at once up to the first whose low 7 bits are all 1 (it may carry 7 bits; the
      // byte-by-byte path below decides), as many as the accumulator has room for. Not fewer
      // instructions than a byte at a time, but a quarter fewer mispredicted branches in a lossless
      // HT decode (the 7-or-8 test per byte), and its tier-1 some 5 % faster.
      if (pos_ >= 8) {
        std::uint64_t word;
        std::memcpy(&word, bytes_.data() + pos_ - 8, sizeof word);
        const std::uint64_t next_first = __builtin_bswap64(word);  // bytes_[pos_ - 1] in the low byte
        // A byte whose low 7 bits are all 1 is a zero byte of this.
        const int first_sevens = lowest_zero_byte(~(next_first | 0x8080808080808080u));
        const int take = std::min((64 - available_) / 8, first_sevens);
        if (take > 0) {
          const std::uint64_t taken = take == 8 ? next_first : next_first & ((std::uint64_t{1} << (8 * take)) - 1);
          acc_ |= taken << available_;
          available_ += 8 * take;
          pos_ -= static_cast<std::size_t>(take);
          last_ = static_cast<std::uint32_t>(taken >> (8 * (take - 1)));
          return;
        }
      }
    }
    std::uint32_t byte = 0;
    if (pos_ > 0) byte = bytes_[--pos_];
    const int bits = last_ > 0x8F && (byte & 0x7F) == 0x7F ? 7 : 8;
    acc_ |= static_cast<std::uint64_t>(byte & ((1u << bits) - 1)) << available_;
    available_ += bits;
    last_ = byte;
  }
  std::span<const std::uint8_t> bytes_;
  std::size_t pos_;
  std::uint64_t acc_ = 0;
  int available_ = 0;
  std::uint32_t last_ = 0;
};

// The SigProp pass's bits (T.814 7.4): bytes forwards from the start of the refinement segment
// Dref, bits least significant first, 7 bits after 0xFF (as MagSgn); past the end, 0s.
class SigPropReader {
 public:
  explicit SigPropReader(std::span<const std::uint8_t> bytes) : bytes_(bytes) {}
  int bit() {
    if (bits_ == 0) {
      bits_ = last_ == 0xFF ? 7 : 8;
      byte_ = pos_ < bytes_.size() ? bytes_[pos_] : 0;
      ++pos_;
      last_ = byte_;
    }
    const int b = byte_ & 1;
    byte_ >>= 1;
    --bits_;
    return b;
  }

 private:
  std::span<const std::uint8_t> bytes_;
  std::size_t pos_ = 0;
  std::uint32_t byte_ = 0, last_ = 0;
  int bits_ = 0;
};

// The MagRef pass's bits (T.814 7.5): bytes backwards from the end of Dref, bits least significant
// first, with the VLC's stuffing rule (a byte after one above 0x8F whose low 7 bits are all 1
// carries 7 bits; the byte before the first counts as 0xFF); past the start, 0s.
class MagRefReader {
 public:
  explicit MagRefReader(std::span<const std::uint8_t> bytes) : bytes_(bytes), pos_(bytes.size()) {}
  int bit() {
    if (bits_ == 0) {
      byte_ = pos_ > 0 ? bytes_[--pos_] : 0;
      bits_ = last_ > 0x8F && (byte_ & 0x7F) == 0x7F ? 7 : 8;
      last_ = byte_;
    }
    const int b = byte_ & 1;
    byte_ >>= 1;
    --bits_;
    return b;
  }

 private:
  std::span<const std::uint8_t> bytes_;
  std::size_t pos_;
  std::uint32_t byte_ = 0, last_ = 0xFF;
  int bits_ = 0;
};

}  // namespace codec::ht
