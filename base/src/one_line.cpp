#include "base/one_line.h"

namespace base {

std::string one_line(std::string_view text) {
  std::string out;
  out.reserve(text.size());
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

}  // namespace base
