// Writing an output file so that it is either complete or absent: the content goes to a new
// temporary file in the same folder (so the final rename stays on one file system and is atomic),
// which is renamed over the target only once fully written. A full disk, a failing writer or a
// crash leaves the target as it was.
#pragma once

#include <functional>
#include <stdexcept>
#include <string>
#include <string_view>

namespace base {

// A file could not be written: what() is "PATH: problem".
class FileError : public std::runtime_error {
 public:
  FileError(const std::string& path, const std::string& problem)
      : std::runtime_error(path + ": " + problem), path_(path), problem_(problem) {}
  const std::string& path() const { return path_; }
  const std::string& problem() const { return problem_; }

 private:
  std::string path_, problem_;
};

// Creates a fresh, empty temporary file next to `path`, named "PATH.tmp-XXXXXXXX.EXT" (the
// extension repeated, for writers that pick a format from the name), calls write(temporary), then
// renames the temporary onto `path`. On any failure, `write` throwing included, the temporary is
// removed and the exception propagates (FileError for the file operations here).
void write_atomically(const std::string& path, const std::function<void(const std::string& temporary)>& write);

// write_atomically of `bytes`, with every write and the final flush checked.
void replace_file_atomically(const std::string& path, std::string_view bytes);

}  // namespace base
