#include "number_pairs.h"

#include <charconv>
#include <stdexcept>

namespace cli {
namespace {

std::int64_t parse_number(std::string_view part, std::string_view text, std::string_view option, std::int64_t max,
                          char separator) {
  std::int64_t value = 0;
  // from_chars would accept a leading '-', so require digits only, and at least one.
  const bool digits_only = !part.empty() && part.find_first_not_of("0123456789") == std::string_view::npos;
  const auto [end, ec] = std::from_chars(part.data(), part.data() + part.size(), value);
  if (!digits_only || ec != std::errc{} || end != part.data() + part.size() || value > max)
    throw std::invalid_argument(std::string(option) + " must be two non-negative integers " +
                                (separator == 'x' ? "WxH" : "X,Y") + " up to " + std::to_string(max) + ", got \"" +
                                std::string(text) + "\"");
  return value;
}

}  // namespace

std::pair<std::int64_t, std::int64_t> parse_pair(std::string_view text, char separator, std::string_view option,
                                                 std::int64_t max) {
  const std::size_t at = text.find(separator);
  if (at == std::string_view::npos) return {parse_number({}, text, option, max, separator), 0};  // throws
  return {parse_number(text.substr(0, at), text, option, max, separator),
          parse_number(text.substr(at + 1), text, option, max, separator)};
}

std::vector<std::pair<std::int64_t, std::int64_t>> parse_size_list(std::string_view text, std::string_view option,
                                                                   std::int64_t max) {
  std::vector<std::pair<std::int64_t, std::int64_t>> out;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = text.find(',', start);
    out.push_back(
        parse_pair(text.substr(start, comma == std::string_view::npos ? std::string_view::npos : comma - start), 'x',
                   option, max));
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  return out;
}

}  // namespace cli
