#pragma once

// Helpers shared by the text headers of PFM and PNM files. Standard library
// only, so the fuzzers can compile the parsers on their own.

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

namespace imageio::detail {

// The whitespace of PFM and Netpbm headers (C's isspace in the "C" locale).
inline bool is_header_space(std::uint8_t ch) {
  return ch == ' ' || ch == '\t' || ch == '\n' || ch == '\r' || ch == '\v' || ch == '\f';
}

// Header fields are short; anything longer is garbage and is cut short in
// messages so that an error stays a readable single line.
inline constexpr std::size_t kMaxTokenLength = 32;

// Makes a header token safe to quote in an error message.
inline std::string printable(std::string_view token) {
  std::string out;
  for (char ch : token.substr(0, kMaxTokenLength)) {
    out += (ch >= 0x20 && ch < 0x7f) ? ch : '?';
  }
  if (token.size() > kMaxTokenLength) out += "...";
  return out;
}

}  // namespace imageio::detail
