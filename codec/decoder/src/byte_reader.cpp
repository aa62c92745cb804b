#include "byte_reader.h"

namespace codec::dec {

void fail_at(std::size_t offset, const std::string& what) {
  throw DecodeError("at byte " + std::to_string(offset) + ": " + what);
}

void ByteReader::need(std::size_t n, const char* field) const {
  if (remaining() < n)
    fail(std::string("truncated: ") + field + " needs " + std::to_string(n) + " byte(s), " +
         std::to_string(remaining()) + " left");
}

std::uint8_t ByteReader::u8(const char* field) {
  need(1, field);
  return bytes_[pos_++];
}

std::uint16_t ByteReader::u16(const char* field) {
  need(2, field);
  const std::uint16_t v = static_cast<std::uint16_t>((bytes_[pos_] << 8) | bytes_[pos_ + 1]);
  pos_ += 2;
  return v;
}

std::uint32_t ByteReader::u32(const char* field) {
  need(4, field);
  std::uint32_t v = 0;
  for (int i = 0; i < 4; ++i) v = (v << 8) | bytes_[pos_ + static_cast<std::size_t>(i)];
  pos_ += 4;
  return v;
}

std::uint64_t ByteReader::u64(const char* field) {
  need(8, field);
  std::uint64_t v = 0;
  for (int i = 0; i < 8; ++i) v = (v << 8) | bytes_[pos_ + static_cast<std::size_t>(i)];
  pos_ += 8;
  return v;
}

std::uint16_t ByteReader::peek_u16() const {
  if (remaining() < 2) return 0;
  return static_cast<std::uint16_t>((bytes_[pos_] << 8) | bytes_[pos_ + 1]);
}

std::span<const std::uint8_t> ByteReader::take(std::size_t n, const char* what) {
  need(n, what);
  auto s = bytes_.subspan(pos_, n);
  pos_ += n;
  return s;
}

}  // namespace codec::dec
