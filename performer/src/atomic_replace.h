// Replacing a file all at once: output files are either complete or untouched, never half written
// by a full disk or a crash mid-write. Private to the library.
#pragma once

#include <filesystem>
#include <string_view>

namespace performer::detail {

// Writes `bytes` to a new temporary file next to `file` (same folder, so the rename stays on one
// file system), then renames it over `file`. On any failure the temporary is removed and
// std::runtime_error ("FILE: problem") is thrown.
void replace_file_atomically(const std::filesystem::path& file, std::string_view bytes);

}  // namespace performer::detail
