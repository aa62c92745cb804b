#pragma once
#include <cstdint>
#include <vector>

namespace codec::t2 {

// Packs packet-header bits into bytes as T.800 B.10.1 requires: MSB first, and after every 0xFF
// byte the next byte carries only seven bits behind a stuffed 0 MSB. The stuffing keeps a header
// from ever holding 0xFF followed by a byte above 0x8F, so no header byte pair reads as a marker
// (SOP/EPH or a delimiting marker) to a decoder that scans for them.
class HeaderBitWriter {
 public:
  // Appends to `out`, which must outlive the writer; bytes already in `out` are left alone.
  explicit HeaderBitWriter(std::vector<std::uint8_t>& out) : out_(out) {}

  // Inline: a packet header is written a bit at a time, and rate control's trials write thousands.
  void put_bit(bool bit) {
    acc_ = static_cast<std::uint8_t>((acc_ << 1) | (bit ? 1 : 0));
    ++bits_;
    if (++filled_ == capacity_) {
      // A seven-bit byte is emitted as is: its MSB is the stuffed 0, so it can never be 0xFF.
      out_.push_back(acc_);
      capacity_ = acc_ == 0xFF ? 7 : 8;
      acc_ = 0;
      filled_ = 0;
    }
  }
  // The low `count` bits of `value`, most significant first; count in 0..64.
  void put_bits(std::uint64_t value, int count);
  // Ends the header: pads the last byte with zeros and, if the last whole byte was 0xFF, appends
  // the 0x00 byte that holds its seven stuffed bits (B.10.1: a header shall not end in 0xFF).
  // The writer may be reused afterwards for a new header.
  void flush();

  // Bits written since construction or the last flush(), not counting stuffing or padding.
  std::uint64_t bits_written() const { return bits_; }

 private:
  std::vector<std::uint8_t>& out_;
  std::uint8_t acc_ = 0;  // bits of the byte being assembled, right-aligned
  int filled_ = 0;        // how many bits acc_ holds
  int capacity_ = 8;      // 7 right after a 0xFF byte, else 8
  std::uint64_t bits_ = 0;
};

}  // namespace codec::t2
