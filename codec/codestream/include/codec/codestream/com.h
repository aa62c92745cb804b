#pragma once
#include <cstdint>
#include <string_view>
#include <vector>

#include "codec/codestream/byte_writer.h"

namespace codec::cs {

// Rcom (T.800 Table A.33): what the comment bytes are.
enum class CommentRegistration : std::uint16_t { Binary = 0, Latin = 1 };

// Comment (T.800 A.9.2). Latin means ISO/IEC 8859-15 text.
struct Comment {
  CommentRegistration registration = CommentRegistration::Latin;
  std::vector<std::uint8_t> data;  // at most 65531 bytes, so Lcom = 4 + n fits 16 bits
};

// A Latin comment holding `text` byte for byte.
Comment latin_comment(std::string_view text);

void write_com(ByteWriter& out, const Comment& com);

}  // namespace codec::cs
