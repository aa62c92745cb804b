#include "performer/detail/atomic_file.h"

#include <sstream>

#include "base/atomic_file.h"

namespace performer::detail {

// The content is formatted in memory first (meshes of a few megabytes), so a failure while
// formatting leaves no file at all; base writes it atomically.
void write_file_atomically(const std::filesystem::path& path, const std::function<void(std::ostream&)>& fill) {
  std::ostringstream content(std::ios::binary);
  fill(content);
  base::replace_file_atomically(path.string(), content.view());
}

}  // namespace performer::detail
