// Platform names: parsing, printing and the GPUJ2K_GL environment override.
#include "glcontext/context.h"
#include "glcontext/error.h"

#include <array>
#include <cstdlib>
#include <string>
#include <utility>

namespace glc {
namespace {

// Single source of truth for the spelling of each platform.
constexpr std::array<std::pair<Platform, std::string_view>, 5> kNames{{
    {Platform::Auto, "auto"},
    {Platform::EglDevice, "egl-device"},
    {Platform::EglSurfaceless, "egl-surfaceless"},
    {Platform::EglDefault, "egl-default"},
    {Platform::OsMesa, "osmesa"},
}};

}  // namespace

Platform parse_platform(std::string_view name) {
  for (const auto& [platform, spelling] : kNames) {
    if (name == spelling) return platform;
  }
  std::string valid;
  for (const auto& entry : kNames) {
    if (!valid.empty()) valid += ", ";
    valid += entry.second;
  }
  throw GlError("unknown GL platform '" + std::string(name) + "' (valid: " + valid + ")");
}

std::string_view platform_name(Platform platform) {
  for (const auto& [p, spelling] : kNames) {
    if (p == platform) return spelling;
  }
  return "unknown";
}

Platform platform_from_env() {
  const char* value = std::getenv("GPUJ2K_GL");
  if (value == nullptr || *value == '\0') return Platform::Auto;
  try {
    return parse_platform(value);
  } catch (const GlError& e) {
    // Name the variable so the user knows where the bad value came from.
    throw GlError(std::string("GPUJ2K_GL: ") + e.what());
  }
}

}  // namespace glc
