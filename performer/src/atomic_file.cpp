#include "atomic_file.h"

#include <sstream>

#include "atomic_replace.h"

namespace performer::detail {

// Built on replace_file_atomically, the one implementation of the temporary-then-rename dance: the
// content is formatted in memory first (meshes of a few megabytes), so a failure while formatting
// leaves no file at all.
void write_file_atomically(const std::filesystem::path& path, const std::function<void(std::ostream&)>& fill) {
  std::ostringstream content(std::ios::binary);
  fill(content);
  replace_file_atomically(path, content.view());
}

}  // namespace performer::detail
