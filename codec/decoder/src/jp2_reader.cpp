#include "jp2_reader.h"

#include <string>

#include "byte_reader.h"

namespace codec::dec {

namespace {

constexpr std::uint32_t box_type(const char (&s)[5]) {
  return (static_cast<std::uint32_t>(static_cast<unsigned char>(s[0])) << 24) |
         (static_cast<std::uint32_t>(static_cast<unsigned char>(s[1])) << 16) |
         (static_cast<std::uint32_t>(static_cast<unsigned char>(s[2])) << 8) | static_cast<unsigned char>(s[3]);
}

struct Box {
  std::uint32_t type;
  std::span<const std::uint8_t> body;
  std::size_t body_offset;
};

// I.4: LBox (4), TBox (4), XLBox (8) when LBox is 1; LBox 0 runs to the end of the enclosing span.
Box next_box(ByteReader& in) {
  const std::size_t at = in.file_offset();
  const std::uint64_t lbox = in.u32("LBox");
  const std::uint32_t type = in.u32("TBox");
  std::uint64_t header = 8, length = lbox;
  if (lbox == 1) {
    length = in.u64("XLBox");
    header = 16;
  } else if (lbox == 0) {
    length = in.remaining() + header;
  }
  if (length < header) fail_at(at, "JP2 box length " + std::to_string(length) + " is shorter than its header");
  if (length - header > in.remaining()) fail_at(at, "JP2 box runs past the end of the file");
  const std::size_t body_offset = in.file_offset();
  return Box{type, in.take(static_cast<std::size_t>(length - header), "JP2 box"), body_offset};
}

}  // namespace

bool looks_like_jp2(std::span<const std::uint8_t> b) {
  static constexpr std::uint8_t kSignature[12] = {0, 0, 0, 0x0C, 'j', 'P', ' ', ' ', 0x0D, 0x0A, 0x87, 0x0A};
  if (b.size() < 12) return false;
  for (int i = 0; i < 12; ++i)
    if (b[static_cast<std::size_t>(i)] != kSignature[i]) return false;
  return true;
}

Jp2File read_jp2(std::span<const std::uint8_t> bytes) {
  Jp2File f;
  ByteReader in(bytes);
  bool have_codestream = false;
  while (!in.at_end() && !have_codestream) {
    const Box box = next_box(in);
    if (box.type == box_type("jp2h")) {
      ByteReader inner(box.body, box.body_offset);
      while (!inner.at_end()) {
        const Box sub = next_box(inner);
        if (sub.type == box_type("colr")) {
          ByteReader colr(sub.body, sub.body_offset);
          const int method = colr.u8("METH");
          colr.u8("PREC");
          colr.u8("APPROX");
          if (method == 1 && f.colour_space == 0) f.colour_space = static_cast<int>(colr.u32("EnumCS"));
        } else if (sub.type == box_type("pclr") || sub.type == box_type("cmap")) {
          fail_at(sub.body_offset - 8, "JP2 palettes (pclr/cmap boxes) are not supported yet");
        }
      }
    } else if (box.type == box_type("jp2c")) {
      f.codestream = box.body;
      f.codestream_offset = box.body_offset;
      have_codestream = true;
    }
  }
  if (!have_codestream) fail_at(bytes.size(), "the JP2 file has no contiguous codestream box (jp2c)");
  return f;
}

}  // namespace codec::dec
