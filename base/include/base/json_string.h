#pragma once

#include <string>
#include <string_view>

namespace base {

// `text` as a JSON string literal: in quotes, quotes and backslashes escaped, control characters
// as \u00XX (RFC 8259, section 7); other bytes, UTF-8 included, as they are.
std::string json_string(std::string_view text);

}  // namespace base
