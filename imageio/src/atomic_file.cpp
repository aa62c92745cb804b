#include "atomic_file.h"

#include "base/atomic_file.h"
#include "imageio/error.h"

namespace imageio::detail {

// base's writer, with its file errors as this library's IoError.
void write_atomically(const std::string& path, const std::function<void(const std::string& temporary_path)>& write) {
  try {
    base::write_atomically(path, write);
  } catch (const base::FileError& e) {
    throw IoError(e.path(), e.problem());
  }
}

}  // namespace imageio::detail
