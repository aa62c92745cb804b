#pragma once
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace codec::cs {

// Appends big-endian integers to a caller's byte vector. Every multi-byte field of the codestream
// (T.800 A.1.3) and of the JP2 boxes (I.4) is big-endian. Lengths such as Lxxx and Psot are only
// known once their content is written, so a field can be written as a placeholder and patched.
//
// The writer refers to the vector, so several writers (main header, tile-parts, packets) can
// append to one buffer; the vector must outlive the writer.
class ByteWriter {
 public:
  explicit ByteWriter(std::vector<std::uint8_t>& out) : out_(&out) {}

  void u8(std::uint8_t v);
  void u16(std::uint16_t v);
  void u32(std::uint32_t v);
  void u64(std::uint64_t v);
  void bytes(std::span<const std::uint8_t> data);

  // Overwrite a field written earlier; throws CodestreamError when it does not lie inside the
  // bytes written so far.
  void patch_u16(std::size_t offset, std::uint16_t v);
  void patch_u32(std::size_t offset, std::uint32_t v);

  // Drop everything from `size` on, so a writer that fails half-way can leave no partial segment.
  void truncate(std::size_t size);

  std::size_t size() const { return out_->size(); }
  const std::vector<std::uint8_t>& data() const { return *out_; }

 private:
  std::vector<std::uint8_t>* out_;
};

}  // namespace codec::cs
