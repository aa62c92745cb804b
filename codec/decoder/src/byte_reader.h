#pragma once
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>

#include "codec/decoder/decoder.h"

namespace codec::dec {

// Throws DecodeError("at byte OFFSET: what").
[[noreturn]] void fail_at(std::size_t offset, const std::string& what);

// Big-endian reads over a span that owns nothing (T.800 A.1.3: every marker segment parameter is
// big-endian). Every read is bounds-checked and names the offset of the failing field; `base` is
// the span's offset in the whole file, so messages point into the file, not into a sub-span.
class ByteReader {
 public:
  ByteReader(std::span<const std::uint8_t> bytes, std::size_t base = 0) : bytes_(bytes), base_(base) {}

  std::size_t position() const { return pos_; }
  std::size_t file_offset() const { return base_ + pos_; }
  std::size_t remaining() const { return bytes_.size() - pos_; }
  bool at_end() const { return pos_ >= bytes_.size(); }

  std::uint8_t u8(const char* field);
  std::uint16_t u16(const char* field);
  std::uint32_t u32(const char* field);
  std::uint64_t u64(const char* field);
  std::uint16_t peek_u16() const;  // 0 when fewer than two bytes remain
  // The next n bytes, as a span into the stream.
  std::span<const std::uint8_t> take(std::size_t n, const char* what);
  void skip(std::size_t n, const char* what) { take(n, what); }
  [[noreturn]] void fail(const std::string& what) const { fail_at(file_offset(), what); }

 private:
  void need(std::size_t n, const char* field) const;
  std::span<const std::uint8_t> bytes_;
  std::size_t base_ = 0;
  std::size_t pos_ = 0;
};

}  // namespace codec::dec
