#include "codec/codestream/byte_writer.h"

#include <string>

#include "codec/codestream/error.h"

namespace codec::cs {
namespace {

void check_patch(std::size_t offset, std::size_t width, std::size_t size) {
  if (offset > size || size - offset < width)
    throw CodestreamError("cannot patch " + std::to_string(width) + " bytes at offset " + std::to_string(offset) +
                          ": only " + std::to_string(size) + " bytes written");
}

}  // namespace

void ByteWriter::u8(std::uint8_t v) { out_->push_back(v); }

void ByteWriter::u16(std::uint16_t v) {
  u8(static_cast<std::uint8_t>(v >> 8));
  u8(static_cast<std::uint8_t>(v));
}

void ByteWriter::u32(std::uint32_t v) {
  u16(static_cast<std::uint16_t>(v >> 16));
  u16(static_cast<std::uint16_t>(v));
}

void ByteWriter::u64(std::uint64_t v) {
  u32(static_cast<std::uint32_t>(v >> 32));
  u32(static_cast<std::uint32_t>(v));
}

void ByteWriter::bytes(std::span<const std::uint8_t> data) { out_->insert(out_->end(), data.begin(), data.end()); }

void ByteWriter::patch_u16(std::size_t offset, std::uint16_t v) {
  check_patch(offset, 2, out_->size());
  (*out_)[offset] = static_cast<std::uint8_t>(v >> 8);
  (*out_)[offset + 1] = static_cast<std::uint8_t>(v);
}

void ByteWriter::patch_u32(std::size_t offset, std::uint32_t v) {
  check_patch(offset, 4, out_->size());
  patch_u16(offset, static_cast<std::uint16_t>(v >> 16));
  patch_u16(offset + 2, static_cast<std::uint16_t>(v));
}

void ByteWriter::truncate(std::size_t size) {
  if (size < out_->size()) out_->resize(size);
}

}  // namespace codec::cs
