#include "performer/phoneme_role.h"

#include <array>
#include <utility>

namespace performer {

namespace {

constexpr std::array<std::pair<PhonemeRole, std::string_view>, 5> kNames = {{
    {PhonemeRole::any, "any"},
    {PhonemeRole::onset, "onset"},
    {PhonemeRole::nucleus, "nucleus"},
    {PhonemeRole::coda, "coda"},
    {PhonemeRole::nasal, "nasal"},
}};

}  // namespace

std::string_view role_name(PhonemeRole role) {
  for (const auto& [r, name] : kNames)
    if (r == role) return name;
  return "?";
}

std::optional<PhonemeRole> parse_role(std::string_view text) {
  for (const auto& [r, name] : kNames)
    if (name == text) return r;
  return std::nullopt;
}

}  // namespace performer
