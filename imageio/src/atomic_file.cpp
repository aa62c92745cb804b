#include "atomic_file.h"

#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <random>

#include "imageio/error.h"

namespace imageio::detail {
namespace {

std::string random_hex(int digits) {
  static thread_local std::mt19937_64 engine{std::random_device{}()};
  static constexpr char kHex[] = "0123456789abcdef";
  std::string out;
  std::uint64_t bits = engine();
  for (int i = 0; i < digits; ++i, bits >>= 4) out += kHex[bits & 15];
  return out;
}

// Returns the name of a newly created empty file "PATH.tmp-XXXXXXXX.EXT".
// The original extension is repeated at the end because some OpenImageIO
// writers choose their variant from the name they are asked to open (e.g.
// JPEG 2000 picks .j2k codestream versus .jp2 container).
std::string create_temporary(const std::string& path) {
  const std::string extension = std::filesystem::path(path).extension().string();
  int error = 0;
  for (int attempt = 0; attempt < 16; ++attempt) {
    std::string candidate = path + ".tmp-" + random_hex(8) + extension;
    // "x" makes creation exclusive, so we never clobber someone else's
    // file that happens to have the same random name.
    if (std::FILE* file = std::fopen(candidate.c_str(), "wbx")) {
      std::fclose(file);
      return candidate;
    }
    error = errno;
    if (error != EEXIST) break;
  }
  throw IoError(path, std::string("cannot create a temporary file next to it: ") + std::strerror(error));
}

}  // namespace

void write_atomically(const std::string& path, const std::function<void(const std::string& temporary_path)>& write) {
  const std::string temporary = create_temporary(path);
  try {
    write(temporary);
    std::error_code ec;
    std::filesystem::rename(temporary, path, ec);
    if (ec) throw IoError(path, "cannot rename temporary file into place: " + ec.message());
  } catch (...) {
    std::error_code ignored;
    std::filesystem::remove(temporary, ignored);
    throw;
  }
}

}  // namespace imageio::detail
