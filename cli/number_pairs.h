// Strict parsing of the "X,Y" and "WxH" option values both command-line tools take.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace cli {

// Two non-negative integers separated by `separator`, each at most `max`. Anything else (signs,
// spaces, missing parts, overflow) throws std::invalid_argument naming `option` and the text.
std::pair<std::int64_t, std::int64_t> parse_pair(std::string_view text, char separator, std::string_view option,
                                                 std::int64_t max);

// A comma-separated list of "WxH" pairs.
std::vector<std::pair<std::int64_t, std::int64_t>> parse_size_list(std::string_view text, std::string_view option,
                                                                   std::int64_t max);

}  // namespace cli
