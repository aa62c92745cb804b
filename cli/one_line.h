// The tools report every failure as exactly one line, whatever the library messages they relay contain.
#pragma once

#include <string>
#include <string_view>

namespace cli {

// Folds line breaks (and the blanks around them) into "; " and drops trailing ones.
inline std::string one_line(std::string_view text) {
  std::string out;
  std::size_t i = 0;
  while (i < text.size()) {
    const char ch = text[i];
    if (ch != '\n' && ch != '\r') {
      out += ch;
      ++i;
      continue;
    }
    while (!out.empty() && (out.back() == ' ' || out.back() == '\t')) out.pop_back();
    while (i < text.size() && (text[i] == '\n' || text[i] == '\r' || text[i] == ' ' || text[i] == '\t')) ++i;
    if (i < text.size() && !out.empty()) out += "; ";
  }
  return out;
}

}  // namespace cli

namespace dwtool {
using cli::one_line;
}  // namespace dwtool
