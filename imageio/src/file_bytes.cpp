#include "file_bytes.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include "imageio/error.h"

namespace imageio::detail {
namespace {

using FilePtr = std::unique_ptr<std::FILE, int (*)(std::FILE*)>;

}  // namespace

std::vector<std::uint8_t> read_whole_file(const std::string& path) {
  FilePtr file(std::fopen(path.c_str(), "rb"), &std::fclose);
  if (!file) throw IoError(path, std::string("cannot open: ") + std::strerror(errno));
  std::vector<std::uint8_t> bytes;
  std::uint8_t chunk[1 << 16];
  while (std::size_t n = std::fread(chunk, 1, sizeof chunk, file.get())) {
    bytes.insert(bytes.end(), chunk, chunk + n);
  }
  if (std::ferror(file.get())) throw IoError(path, std::string("read error: ") + std::strerror(errno));
  return bytes;
}

FileBytes::FileBytes(const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd >= 0) {
    struct stat info {};
    if (::fstat(fd, &info) == 0 && S_ISREG(info.st_mode) && info.st_size > 0) {
      const auto size = static_cast<std::size_t>(info.st_size);
      void* map = ::mmap(nullptr, size, PROT_READ, MAP_PRIVATE | MAP_POPULATE, fd, 0);
      if (map != MAP_FAILED) {
        map_ = map;
        mapped_size_ = size;
        bytes_ = std::span(static_cast<const std::uint8_t*>(map), size);
      }
    }
    ::close(fd);
  }
  if (map_ == nullptr) {
    copy_ = read_whole_file(path);  // names the file in any error
    bytes_ = copy_;
  }
}

FileBytes::~FileBytes() {
  if (map_ != nullptr) ::munmap(map_, mapped_size_);
}

void write_whole_file(const std::string& path, const std::string& file_name, std::span<const std::uint8_t> bytes) {
  bool written = false;
  write_file_in_chunks(path, file_name, [&] {
    const std::span<const std::uint8_t> chunk = written ? std::span<const std::uint8_t>() : bytes;
    written = true;
    return chunk;
  });
}

void write_file_in_chunks(const std::string& path, const std::string& file_name,
                          const std::function<std::span<const std::uint8_t>()>& next_chunk) {
  FilePtr file(std::fopen(file_name.c_str(), "wb"), &std::fclose);
  if (!file) throw IoError(path, std::string("cannot open for writing: ") + std::strerror(errno));
  for (std::span<const std::uint8_t> chunk = next_chunk(); !chunk.empty(); chunk = next_chunk())
    if (std::fwrite(chunk.data(), 1, chunk.size(), file.get()) != chunk.size())
      throw IoError(path, std::string("write error: ") + std::strerror(errno));
  // fclose flushes; a full disk may only show up here.
  if (std::fclose(file.release()) != 0) {
    throw IoError(path, std::string("write error: ") + std::strerror(errno));
  }
}

}  // namespace imageio::detail
