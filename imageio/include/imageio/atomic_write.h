#pragma once
#include <cstdint>
#include <span>
#include <string>

namespace imageio {

// Writes `bytes` to `path` through a temporary file in the same folder that is renamed into place,
// so `path` is either complete or untouched (an encoder's output is never left half written).
// Errors are IoError("PATH: problem").
void write_bytes_atomically(const std::string& path, std::span<const std::uint8_t> bytes);

}  // namespace imageio
