#include "base/atomic_file.h"

#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <random>
#include <system_error>

namespace base {
namespace {

std::string random_hex(int digits) {
  static thread_local std::mt19937_64 engine{std::random_device{}()};
  static constexpr char kHex[] = "0123456789abcdef";
  std::string out;
  std::uint64_t bits = engine();
  for (int i = 0; i < digits; ++i, bits >>= 4) out += kHex[bits & 15];
  return out;
}

std::string create_temporary(const std::string& path) {
  const std::string extension = std::filesystem::path(path).extension().string();
  int error = 0;
  for (int attempt = 0; attempt < 16; ++attempt) {
    std::string candidate = path + ".tmp-" + random_hex(8) + extension;
    // "x" makes the creation exclusive: another writer's temporary of the same name is never
    // clobbered; try another name.
    if (std::FILE* file = std::fopen(candidate.c_str(), "wbx")) {
      std::fclose(file);
      return candidate;
    }
    error = errno;
    if (error != EEXIST) break;
  }
  throw FileError(path, std::string("cannot create a temporary file next to it: ") + std::strerror(error));
}

}  // namespace

void write_atomically(const std::string& path, const std::function<void(const std::string& temporary)>& write) {
  const std::string temporary = create_temporary(path);
  try {
    write(temporary);
    std::error_code ec;
    std::filesystem::rename(temporary, path, ec);
    if (ec) throw FileError(path, "cannot rename the temporary file into place: " + ec.message());
  } catch (...) {
    std::error_code ignored;
    std::filesystem::remove(temporary, ignored);
    throw;
  }
}

void replace_file_atomically(const std::string& path, std::string_view bytes) {
  write_atomically(path, [&](const std::string& temporary) {
    std::FILE* out = std::fopen(temporary.c_str(), "wb");
    if (out == nullptr) throw FileError(path, std::string("cannot open the temporary file: ") + std::strerror(errno));
    const bool written = std::fwrite(bytes.data(), 1, bytes.size(), out) == bytes.size();
    const int write_error = errno;
    // fclose flushes: a full disk can show up only here.
    const bool closed = std::fclose(out) == 0;
    if (!written) throw FileError(path, std::string("write failed: ") + std::strerror(write_error));
    if (!closed) throw FileError(path, std::string("write failed: ") + std::strerror(errno));
  });
}

}  // namespace base
