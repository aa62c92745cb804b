// Writing an output file so that it is either complete or absent: the content goes to a temporary
// file in the same folder (so the final rename stays on one file system and is atomic), which is
// renamed over the target only once fully written and flushed. Not public API: shared by the mesh and
// glTF writers.
#pragma once

#include <filesystem>
#include <functional>
#include <ostream>

namespace performer::detail {

// Calls fill(stream) on a binary stream to a temporary file next to `path`, then renames it to
// `path`. On any failure (cannot create, fill throws, a write fails, rename fails) the temporary
// file is removed and `path` is left as it was. Throws std::runtime_error "PATH: problem"; an
// exception from fill propagates unchanged.
void write_file_atomically(const std::filesystem::path& path, const std::function<void(std::ostream&)>& fill);

}  // namespace performer::detail
