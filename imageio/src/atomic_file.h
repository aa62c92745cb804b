#pragma once

#include <functional>
#include <string>

namespace imageio::detail {

// Creates a fresh, empty temporary file next to `path` (same directory, so the
// final rename cannot cross file systems), calls write(temporary_path), then
// renames the temporary onto `path`. If anything fails, including `write`
// throwing, the temporary is removed and the exception propagates: `path` is
// either fully written or untouched.
void write_atomically(const std::string& path, const std::function<void(const std::string& temporary_path)>& write);

}  // namespace imageio::detail
