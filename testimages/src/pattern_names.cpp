#include <array>
#include <stdexcept>
#include <string>
#include <utility>

#include "testimages/patterns.h"

namespace testimages {
namespace {

// The command-line names; one table so parsing and printing cannot disagree.
constexpr std::array<std::pair<Pattern, std::string_view>, 7> kNames = {{
    {Pattern::ZonePlate, "zoneplate"},
    {Pattern::GradientH, "gradient-h"},
    {Pattern::GradientV, "gradient-v"},
    {Pattern::GradientDiag, "gradient-diag"},
    {Pattern::Edges, "edges"},
    {Pattern::Noise, "noise"},
    {Pattern::Mix, "mix"},
}};

}  // namespace

Pattern parse_pattern(std::string_view name) {
  for (const auto& [pattern, pattern_name] : kNames) {
    if (name == pattern_name) return pattern;
  }
  std::string message = "unknown pattern \"" + std::string(name) + "\"; expected one of:";
  for (std::size_t i = 0; i < kNames.size(); ++i) {
    message += (i == 0 ? " " : ", ") + std::string(kNames[i].second);
  }
  throw std::invalid_argument(message);
}

std::string_view pattern_name(Pattern pattern) {
  for (const auto& [candidate, name] : kNames) {
    if (candidate == pattern) return name;
  }
  throw std::invalid_argument("invalid Pattern value " + std::to_string(int(pattern)));
}

}  // namespace testimages
