#include "atomic_replace.h"

#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <random>
#include <stdexcept>
#include <string>
#include <system_error>

namespace performer::detail {

namespace {

std::string random_suffix() {
  static thread_local std::mt19937_64 engine{std::random_device{}()};
  constexpr char kHex[] = "0123456789abcdef";
  std::string out;
  for (std::uint64_t bits = engine(), i = 0; i < 12; ++i, bits >>= 4) out += kHex[bits & 15];
  return out;
}

std::runtime_error failure(const std::filesystem::path& file, const std::string& problem) {
  return std::runtime_error(file.string() + ": " + problem);
}

// Opens a new file "FILE.tmp-XXXXXXXXXXXX" for writing. "x" makes the creation exclusive, so an
// existing file of that name (another writer's temporary) is never clobbered: retry with another.
std::FILE* create_temporary(const std::filesystem::path& file, std::filesystem::path& temporary) {
  int error = 0;
  for (int attempt = 0; attempt < 16; ++attempt) {
    temporary = file;
    temporary += ".tmp-" + random_suffix();
    if (std::FILE* out = std::fopen(temporary.c_str(), "wbx")) return out;
    error = errno;
    if (error != EEXIST) break;
  }
  throw failure(file, std::string("cannot create a temporary file next to it: ") + std::strerror(error));
}

void write_and_close(std::FILE* out, std::string_view bytes, const std::filesystem::path& file) {
  const bool written = std::fwrite(bytes.data(), 1, bytes.size(), out) == bytes.size();
  const int write_error = errno;
  // fclose flushes: a full disk can show up only here.
  const bool closed = std::fclose(out) == 0;
  if (!written) throw failure(file, std::string("write failed: ") + std::strerror(write_error));
  if (!closed) throw failure(file, std::string("write failed: ") + std::strerror(errno));
}

}  // namespace

void replace_file_atomically(const std::filesystem::path& file, std::string_view bytes) {
  std::filesystem::path temporary;
  std::FILE* out = create_temporary(file, temporary);
  try {
    write_and_close(out, bytes, file);
    std::error_code ec;
    std::filesystem::rename(temporary, file, ec);
    if (ec) throw failure(file, "cannot rename the temporary file into place: " + ec.message());
  } catch (...) {
    std::error_code ignored;
    std::filesystem::remove(temporary, ignored);
    throw;
  }
}

}  // namespace performer::detail
