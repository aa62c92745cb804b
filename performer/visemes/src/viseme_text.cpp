#include "performer/detail/viseme_text.h"

#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>
#include <system_error>

#include "performer/viseme_error.h"

namespace performer::detail {

namespace {

bool blank(char c) { return c == ' ' || c == '\t'; }

std::string_view trim(std::string_view s) {
  while (!s.empty() && blank(s.front())) s.remove_prefix(1);
  while (!s.empty() && blank(s.back())) s.remove_suffix(1);
  return s;
}

}  // namespace

std::vector<TextLine> content_lines(std::string_view text, bool strip_comments) {
  constexpr std::string_view kBom = "\xEF\xBB\xBF";
  if (text.starts_with(kBom)) text.remove_prefix(kBom.size());
  std::vector<TextLine> lines;
  int number = 1;
  std::size_t pos = 0;
  while (pos < text.size()) {
    std::size_t end = text.find_first_of("\r\n", pos);
    if (end == std::string_view::npos) end = text.size();
    std::string_view line = text.substr(pos, end - pos);
    if (strip_comments) line = line.substr(0, line.find('#'));
    line = trim(line);
    if (!line.empty()) lines.push_back({line, number});
    // CRLF is one line end, a lone CR (old Mac files) or LF another.
    pos = end;
    if (pos < text.size() && text[pos] == '\r') ++pos;
    if (pos < text.size() && text[pos] == '\n') ++pos;
    ++number;
  }
  return lines;
}

std::vector<std::string_view> split_fields(std::string_view line) {
  std::vector<std::string_view> fields;
  std::size_t pos = 0;
  while (pos < line.size()) {
    while (pos < line.size() && blank(line[pos])) ++pos;
    std::size_t end = pos;
    while (end < line.size() && !blank(line[end])) ++end;
    if (end > pos) fields.push_back(line.substr(pos, end - pos));
    pos = end;
  }
  return fields;
}

std::optional<double> parse_number(std::string_view field) {
  // from_chars rejects a leading '+', which hand-written files may have.
  if (field.size() > 1 && field[0] == '+') field.remove_prefix(1);
  double value = 0.0;
  const auto [ptr, ec] = std::from_chars(field.data(), field.data() + field.size(), value);
  if (ec != std::errc() || ptr != field.data() + field.size() || !std::isfinite(value)) return std::nullopt;
  return value;
}

std::optional<int> parse_index(std::string_view field) {
  int value = 0;
  const auto [ptr, ec] = std::from_chars(field.data(), field.data() + field.size(), value);
  if (ec != std::errc() || ptr != field.data() + field.size() || value < 0) return std::nullopt;
  return value;
}

std::string read_text_file(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw VisemeDataError(file.string(), 0, "cannot open");
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw VisemeDataError(file.string(), 0, "read error");
  return std::move(text).str();
}

}  // namespace performer::detail
