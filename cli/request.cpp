#include "request.h"

#include "number_pairs.h"

#include <charconv>
#include <cstdint>
#include <stdexcept>
#include <string_view>

#include "dwt/boundary.h"
#include "dwt/kernel.h"

namespace dwtool {

namespace {

// Reference-grid coordinates are below 2^32 in JPEG 2000 (T.800 Table A.9).
constexpr std::int64_t kMaxCoordinate = (std::int64_t{1} << 32) - 1;
// More threads than this only costs start-up time; a typo like 10000 should not spawn them.
constexpr int kMaxThreads = 1024;

BackendKind parse_backend(const std::string& name) {
  if (name == "cpu") return BackendKind::Cpu;
  if (name == "gpu") return BackendKind::Gpu;
  throw std::invalid_argument("unknown backend '" + name + "' (expected cpu or gpu)");
}

}  // namespace

dwt::Origin parse_origin(const std::string& text) {
  const auto [x, y] = cli::parse_pair(text, ',', "--origin", kMaxCoordinate);
  return dwt::Origin{x, y};
}

Request resolve(const RawOptions& raw) {
  Request r;
  r.direction = raw.direction;
  r.input = raw.input;
  r.output = raw.output;
  r.params.kernel = dwt::parse_kernel(raw.kernel);
  r.params.boundary = dwt::parse_boundary(raw.boundary);
  // Checked against the plane size by dwt::validate once the input is read; only the sign is known now.
  if (raw.levels < 0) throw std::invalid_argument("--levels must be non-negative, got " + std::to_string(raw.levels));
  r.params.levels = raw.levels;
  r.params.origin = parse_origin(raw.origin);
  r.backend = parse_backend(raw.backend);
  if (raw.threads < 0 || raw.threads > kMaxThreads) {
    throw std::invalid_argument("--threads must be 0 (all hardware threads) or 1.." + std::to_string(kMaxThreads) +
                                ", got " + std::to_string(raw.threads));
  }
  r.threads = raw.threads;
  if (raw.bits != 8 && raw.bits != 16) {
    throw std::invalid_argument("--bits must be 8 or 16, got " + std::to_string(raw.bits));
  }
  r.bits = raw.bits;
  if (!raw.gl.empty()) r.gl = glc::parse_platform(raw.gl);
  r.quiet = raw.quiet;
  return r;
}

}  // namespace dwtool
