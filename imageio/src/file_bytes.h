#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace imageio::detail {

// Whole-file byte access for the formats we parse ourselves (PFM, PNM).
// Errors are IoError(path, ...).

std::vector<std::uint8_t> read_whole_file(const std::string& path);

// Writes `bytes` to `file_name` (typically the temporary of
// write_atomically); messages name `path`, the file the caller asked for.
void write_whole_file(const std::string& path, const std::string& file_name, std::span<const std::uint8_t> bytes);

}  // namespace imageio::detail
