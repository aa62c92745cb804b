#include "wavelet_apps/band_spec.h"

#include <charconv>
#include <cmath>

namespace wavelet_apps {

namespace {

[[noreturn]] void fail(std::string_view text, const std::string& problem) {
  throw AppError("band spec '" + std::string(text) + "': " + problem);
}

std::string joined(std::span<const std::string> names) {
  std::string out;
  for (const std::string& n : names) out += (out.empty() ? "" : ", ") + n;
  return out;
}

std::vector<std::string_view> split(std::string_view s, char sep) {
  std::vector<std::string_view> parts;
  std::size_t start = 0;
  for (;;) {
    const std::size_t at = s.find(sep, start);
    parts.push_back(s.substr(start, at == std::string_view::npos ? std::string_view::npos : at - start));
    if (at == std::string_view::npos) return parts;
    start = at + 1;
  }
}

bool is_channel(std::string_view part, std::span<const std::string> channels, int& index) {
  for (std::size_t i = 0; i < channels.size(); ++i)
    if (part == channels[i]) {
      index = static_cast<int>(i);
      return true;
    }
  return false;
}

std::optional<dwt::Orientation> parse_orientation(std::string_view s) {
  if (s == "HL") return dwt::Orientation::HL;
  if (s == "LH") return dwt::Orientation::LH;
  if (s == "HH") return dwt::Orientation::HH;
  return std::nullopt;
}

// "[CHANNEL:]BAND" of the spec `text`.
BandSelector parse_selector(std::string_view text, std::string_view lhs, std::span<const std::string> channels,
                            int levels) {
  BandSelector where;
  std::vector<std::string_view> parts = split(lhs, ':');
  // A leading part that is a channel name (or "*" followed by a band) names the channel.
  int channel = -1;
  if (parts.size() >= 2 && is_channel(parts[0], channels, channel)) {
    where.channel = channel;
    parts.erase(parts.begin());
  } else if (parts.size() == 3 && parts[0] == "*") {
    parts.erase(parts.begin());
  } else if (parts.size() == 3) {
    fail(text, "unknown channel '" + std::string(parts[0]) + "' (expected " + joined(channels) + " or *)");
  }
  if (parts.size() == 1) {
    if (parts[0] == "LL") {
      where.lowest = true;
      return where;
    }
    if (parts[0] == "*") {
      where.every_band = true;
      return where;
    }
    fail(text, "unknown band '" + std::string(parts[0]) + "' (expected LL, *, or LEVEL:HL|LH|HH|*)");
  }
  if (parts.size() != 2) fail(text, "expected [CHANNEL:]BAND=OPERATION with BAND LL, *, or LEVEL:HL|LH|HH|*");
  if (parts[0] != "*") {
    int level = 0;
    const auto [end, ec] = std::from_chars(parts[0].data(), parts[0].data() + parts[0].size(), level);
    if (ec != std::errc() || end != parts[0].data() + parts[0].size() || level < 1)
      fail(text, "unknown level '" + std::string(parts[0]) + "' (expected 1.." + std::to_string(levels) +
                     " or *; channels are " + joined(channels) + ")");
    if (level > levels)
      fail(text, "level " + std::to_string(level) + " exceeds the " + std::to_string(levels) + " decomposition levels");
    where.level = level;
  }
  if (parts[1] != "*") {
    where.orientation = parse_orientation(parts[1]);
    if (!where.orientation)
      fail(text, "unknown orientation '" + std::string(parts[1]) + "' (expected HL, LH, HH or *)");
  }
  return where;
}

std::pair<std::string_view, std::string_view> split_assignment(std::string_view text) {
  const std::size_t eq = text.find('=');
  if (eq == std::string_view::npos || eq == 0 || eq + 1 == text.size())
    fail(text, "expected [CHANNEL:]BAND=OPERATION, e.g. Y:1:*=1.8");
  return {text.substr(0, eq), text.substr(eq + 1)};
}

float parse_factor(std::string_view text, std::string_view op) {
  if (op == "zero") return 0.0f;
  if (op == "keep") return 1.0f;
  float value = 0;
  const auto [end, ec] = std::from_chars(op.data(), op.data() + op.size(), value);
  if (ec != std::errc() || end != op.data() + op.size() || !std::isfinite(value))
    fail(text, "'" + std::string(op) + "' is not a number, zero or keep");
  return value;
}

}  // namespace

bool BandSelector::matches(int channel_index, const dwt::BandId& band, int levels) const {
  if (channel >= 0 && channel != channel_index) return false;
  if (every_band) return true;
  const bool is_lowest = band.orientation == dwt::Orientation::LL;
  if (lowest) return is_lowest;
  if (is_lowest) return false;
  (void)levels;
  if (level != 0 && level != band.level) return false;
  return !orientation || *orientation == band.orientation;
}

ScaleSpec parse_scale_spec(std::string_view text, std::span<const std::string> channels, int levels) {
  const auto [lhs, op] = split_assignment(text);
  ScaleSpec spec;
  spec.text = std::string(text);
  spec.where = parse_selector(text, lhs, channels, levels);
  spec.factor = parse_factor(text, op);
  return spec;
}

std::string_view rule_names() { return "max|base|detail|sum|zero"; }

RuleSpec parse_rule_spec(std::string_view text, std::span<const std::string> channels, int levels) {
  const auto [lhs, op] = split_assignment(text);
  RuleSpec spec;
  spec.text = std::string(text);
  spec.where = parse_selector(text, lhs, channels, levels);
  if (op == "max")
    spec.rule = dwt::BandRule::LargerMagnitude;
  else if (op == "base")
    spec.rule = dwt::BandRule::First;
  else if (op == "detail")
    spec.rule = dwt::BandRule::Second;
  else if (op == "sum")
    spec.rule = dwt::BandRule::Sum;
  else if (op == "zero")
    spec.first_factor = 0.0f;
  else
    fail(text, "unknown rule '" + std::string(op) + "' (expected " + std::string(rule_names()) + ")");
  return spec;
}

namespace {

template <class Spec, class Apply>
std::vector<dwt::BandOperation> operations(std::span<const Spec> specs, int channel, int width, int height,
                                           const dwt::DwtParams& params, Apply&& apply) {
  const auto levels = dwt::decomposition(width, height, params.origin, params.levels);
  std::vector<dwt::BandOperation> ops;
  for (const dwt::BandId& band : dwt::all_bands(params.levels)) {
    dwt::BandOperation op;
    op.rect = dwt::band_rect(levels, band, width, height);
    apply(op, nullptr);
    for (const Spec& spec : specs)
      if (spec.where.matches(channel, band, params.levels)) apply(op, &spec);
    ops.push_back(op);
  }
  return ops;
}

}  // namespace

std::vector<dwt::BandOperation> scale_operations(std::span<const ScaleSpec> specs, int channel, int width, int height,
                                                 const dwt::DwtParams& params) {
  return operations(specs, channel, width, height, params, [](dwt::BandOperation& op, const ScaleSpec* spec) {
    op.rule = dwt::BandRule::First;
    op.first_factor = spec ? spec->factor : 1.0f;
  });
}

std::vector<dwt::BandOperation> rule_operations(std::span<const RuleSpec> specs, int channel, int width, int height,
                                                const dwt::DwtParams& params, const RuleSpec& fallback) {
  return operations(specs, channel, width, height, params, [&](dwt::BandOperation& op, const RuleSpec* spec) {
    const RuleSpec& s = spec ? *spec : fallback;
    op.rule = s.rule;
    op.first_factor = s.first_factor;
    op.second_factor = s.second_factor;
  });
}

}  // namespace wavelet_apps
