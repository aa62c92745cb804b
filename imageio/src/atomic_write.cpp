#include "imageio/atomic_write.h"

#include "atomic_file.h"
#include "file_bytes.h"

namespace imageio {

void write_bytes_atomically(const std::string& path, std::span<const std::uint8_t> bytes) {
  detail::write_atomically(path,
                           [&](const std::string& temporary) { detail::write_whole_file(path, temporary, bytes); });
}

}  // namespace imageio
