#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

// The three bit-streams of an HT cleanup segment (T.814 7.1) and how their bytes are stuffed so
// that no byte pair 0xFF, 0x90..0xFF (a marker) appears in the codestream. The byte layout is
// MagSgn bytes forwards, MEL bytes forwards, then the VLC bytes backwards from the segment's end.
// The refinement segment's two streams are packed alike: SigProp as MagSgn, MagRef as the VLC.

namespace codec::ht {

// Bits packed least significant first, forwards; a byte following 0xFF carries only 7 bits, its
// most significant bit a stuffed 0. MagSgn (T.814 7.1.2) and SigProp (7.1.5) are such streams; they
// differ in how they end.
class ForwardStuffedPacker {
 public:
  // Room for `bytes` bytes up front: a block's stream then grows without reallocating.
  void reserve(std::size_t bytes) { bytes_.reserve(bytes); }
  // The low `count` bits of `bits`, least significant first (count <= 32).
  void put(std::uint32_t bits, int count) {
    if (count == 0) return;
    acc_ |= static_cast<std::uint64_t>(bits & (0xFFFFFFFFu >> (32 - count))) << used_;
    used_ += count;
    while (used_ >= capacity_) flush_byte();
  }
  // The same for up to kWideBits bits, which must be `bits`' only ones (fewer than 8 are pending
  // between calls, so they fit the 64-bit accumulator).
  static constexpr int kWideBits = 56;
  void put_wide(std::uint64_t bits, int count) {
    acc_ |= bits << used_;
    used_ += count;
    while (used_ >= capacity_) flush_byte();
  }

 protected:
  // The next `capacity_` bits (8, or 7 after 0xFF: bit 7 is then a stuffed 0) as one byte.
  void flush_byte() {
    const auto byte = static_cast<std::uint8_t>(acc_ & ((1u << capacity_) - 1));
    bytes_.push_back(byte);
    acc_ >>= capacity_;
    used_ -= capacity_;
    capacity_ = byte == 0xFF ? 7 : 8;
  }
  std::vector<std::uint8_t> bytes_;
  std::uint64_t acc_ = 0;  // bits not yet in a byte, the next one lowest
  int used_ = 0, capacity_ = 8;
};

// MagSgn (T.814 7.1.2).
class MagSgnPacker : public ForwardStuffedPacker {
 public:
  // Pads the last byte with 1s (a decoder reads 0xFF past the segment's MagSgn part, so the pad
  // is what it would read anyway) and drops a final 0xFF, which the decoder's padding reproduces
  // and which would otherwise form a marker with a following MEL or VLC byte.
  std::vector<std::uint8_t> finish() {
    if (used_ > 0) {
      const std::uint32_t tmp = static_cast<std::uint32_t>(acc_) | ((0xFFu << used_) & ((1u << capacity_) - 1));
      if (tmp != 0xFF) bytes_.push_back(static_cast<std::uint8_t>(tmp));
    } else if (!bytes_.empty() && bytes_.back() == 0xFF) {
      bytes_.pop_back();
    }
    return std::move(bytes_);
  }
};

// SigProp (T.814 7.1.5), at the start of the HT refinement segment.
class SigPropPacker : public ForwardStuffedPacker {
 public:
  // A decoder reads 0s past the bits it needs, so the last byte is padded with 0s; a last 0xFF is
  // followed by a 0 byte (a stuffed byte of padding): the MagRef bytes that follow in the segment,
  // or the next packet's, must not form a marker with it.
  std::vector<std::uint8_t> finish() {
    if (used_ > 0) bytes_.push_back(static_cast<std::uint8_t>(acc_));
    if (!bytes_.empty() && bytes_.back() == 0xFF) bytes_.push_back(0x00);
    return std::move(bytes_);
  }
};

// The MEL bit packer (T.814 7.1.3): bits most significant first; after 0xFF, 7 bits.
class MelPacker {
 public:
  void reserve(std::size_t bytes) { bytes_.reserve(bytes); }
  void put_bit(int bit) {
    tmp_ = (tmp_ << 1) | static_cast<std::uint32_t>(bit);
    if (--remaining_ == 0) {
      bytes_.push_back(static_cast<std::uint8_t>(tmp_));
      remaining_ = tmp_ == 0xFF ? 7 : 8;
      tmp_ = 0;
    }
  }
  // A byte is pending when remaining < 8: bits were put, or the previous byte was 0xFF and the
  // next must still carry its stuffed 0.
  bool has_partial_byte() const { return remaining_ < 8; }
  std::uint8_t partial_byte() const { return static_cast<std::uint8_t>(tmp_ << remaining_); }
  std::uint8_t partial_mask() const { return static_cast<std::uint8_t>(0xFFu << remaining_); }
  std::vector<std::uint8_t>& bytes() { return bytes_; }

 private:
  std::vector<std::uint8_t> bytes_;
  std::uint32_t tmp_ = 0;
  int remaining_ = 8;
};

// The MEL adaptive run-length coder (T.814 7.1.3, 7.3.3): a run of 0 symbols reaching 2^E[k]
// sends a 1 and raises the state k; a 1 symbol sends 0 and the run so far in E[k] bits, most
// significant first, and lowers k. E is the standard's 13-entry exponent table.
class MelEncoder {
 public:
  void reserve(std::size_t bytes) { packer_.reserve(bytes); }
  void encode(bool symbol) {
    if (!symbol) {
      if (++run_ == full_run()) end_full_run();
      return;
    }
    packer_.put_bit(0);
    for (int i = kExponent[state_] - 1; i >= 0; --i) packer_.put_bit((run_ >> i) & 1);
    run_ = 0;
    if (state_ > 0) --state_;
  }
  // `count` 0 symbols, as many calls of encode(false) would code them (encode keeps its one-symbol
  // step: it is the cleanup's commonest call).
  void encode_zeros(int count) {
    while (count > 0) {
      const int room = full_run() - run_;
      if (count < room) {
        run_ += count;
        return;
      }
      count -= room;
      end_full_run();
    }
  }
  // A pending run is closed with a 1 (a full run): the decoder reads zeros past the last symbol
  // it needs, which it never uses.
  MelPacker& finish() {
    if (run_ > 0) packer_.put_bit(1);
    run_ = 0;
    return packer_;
  }

 private:
  static constexpr int kExponent[13] = {0, 0, 0, 1, 1, 1, 2, 2, 2, 3, 3, 4, 5};
  // A run of 2^E[k] 0 symbols sends a 1 and raises the state.
  int full_run() const { return 1 << kExponent[state_]; }
  void end_full_run() {
    packer_.put_bit(1);
    run_ = 0;
    if (state_ < 12) ++state_;
  }
  MelPacker packer_;
  int state_ = 0, run_ = 0;
};

// The VLC packer (T.814 7.1.4): bits least significant first into bytes that are laid out
// backwards from the end of the segment. The first byte written is a placeholder for the high
// 8 bits of Scup and the next starts with 4 bits standing for its low nibble (both are filled in at
// the end). A byte after one above 0x8F whose low 7 bits are all 1 carries a stuffed 0 in bit 7.
class VlcPacker {
 public:
  VlcPacker() : bytes_{0xFF} {}
  // The same stream without Scup's placeholder bits: MagRef's (T.814 7.1.6), at the end of the HT
  // refinement segment, which the decoder starts as if a byte above 0x8F preceded it.
  struct WithoutScup {};
  explicit VlcPacker(WithoutScup) : acc_(0), used_(0) {}
  void reserve(std::size_t bytes) { bytes_.reserve(bytes); }
  // The low `count` bits of `bits`, least significant first (count <= 32).
  void put(std::uint32_t bits, int count) {
    if (count == 0) return;
    acc_ |= static_cast<std::uint64_t>(bits & (0xFFFFFFFFu >> (32 - count))) << used_;
    used_ += count;
    for (;;) {
      // A byte after one above 0x8F whose low 7 bits are all 1 is complete with a stuffed 0 (its
      // 7 bits then suffice). Worked out without a branch: which case holds is the data's.
      const int stuffed = (last_ > 0x8F ? 1 : 0) & ((acc_ & 0x7F) == 0x7F ? 1 : 0);
      const int bits = 8 - stuffed;
      if (used_ < bits) break;
      emit(static_cast<std::uint32_t>(acc_ & ((1u << bits) - 1)), bits);
    }
  }
  bool has_partial_byte() const { return used_ > 0; }
  std::uint8_t partial_byte() const { return static_cast<std::uint8_t>(acc_); }
  std::uint8_t partial_mask() const { return static_cast<std::uint8_t>((1u << used_) - 1); }
  // Whether the pending byte is the one that holds Scup's low nibble (then it may not be fused
  // with the MEL's last byte: the nibble would overwrite MEL bits).
  bool partial_is_scup_byte() const { return bytes_.size() == 1; }
  // For a stream without Scup: its bytes in the order written (the segment's last byte first), the
  // pending one 0-padded (a decoder reads 0s past the end).
  std::vector<std::uint8_t> finish_without_scup() {
    if (has_partial_byte()) bytes_.push_back(partial_byte());
    return std::move(bytes_);
  }
  // Bytes in the order written (the segment's last byte first).
  std::vector<std::uint8_t>& bytes() { return bytes_; }

 private:
  void emit(std::uint32_t byte, int bits) {
    bytes_.push_back(static_cast<std::uint8_t>(byte));
    last_ = byte;
    acc_ >>= bits;
    used_ -= bits;
  }
  std::vector<std::uint8_t> bytes_;
  std::uint64_t acc_ = 0xF;  // bits not yet in a byte (at most 7 between calls), the next one lowest
  int used_ = 4;
  std::uint32_t last_ = 0xFF;
};

}  // namespace codec::ht
