#pragma once

#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

namespace imageio::detail {

// Whole-file byte access for the formats we parse ourselves (PFM, PNM).
// Errors are IoError(path, ...).

// Reads in chunks to the end: for pipes and devices (FileBytes maps regular files instead).
std::vector<std::uint8_t> read_whole_file(const std::string& path);

// A whole file's bytes, read-only: mapped from the page cache for a regular file (no copy, no fresh
// memory to fault in), read into memory otherwise (pipes, devices, or if mapping fails). A file
// truncated by another process while it is mapped would fault (SIGBUS); the readers take no
// more care of that race than any mmap-based reader does.
class FileBytes {
 public:
  explicit FileBytes(const std::string& path);
  ~FileBytes();
  FileBytes(const FileBytes&) = delete;
  FileBytes& operator=(const FileBytes&) = delete;
  std::span<const std::uint8_t> bytes() const { return bytes_; }

 private:
  void* map_ = nullptr;
  std::size_t mapped_size_ = 0;
  std::vector<std::uint8_t> copy_;
  std::span<const std::uint8_t> bytes_;
};

// Writes `bytes` to `file_name` (typically the temporary of
// write_atomically); messages name `path`, the file the caller asked for.
void write_whole_file(const std::string& path, const std::string& file_name, std::span<const std::uint8_t> bytes);

// The same for a file made chunk by chunk: writes what `next_chunk` returns until it returns an
// empty span (an exception from it ends the write), so that a large raster need not exist whole.
void write_file_in_chunks(const std::string& path, const std::string& file_name,
                          const std::function<std::span<const std::uint8_t>()>& next_chunk);

}  // namespace imageio::detail
