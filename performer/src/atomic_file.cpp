#include "atomic_file.h"

#include <fstream>
#include <random>
#include <stdexcept>
#include <string>
#include <system_error>

namespace performer::detail {

namespace {

// A name no concurrent writer of the same file picks: the target's name plus a random suffix.
std::filesystem::path temporary_name(const std::filesystem::path& path) {
  std::random_device rd;
  const auto suffix = std::to_string(rd()) + std::to_string(rd());
  std::filesystem::path tmp = path;
  tmp += ".tmp" + suffix;
  return tmp;
}

}  // namespace

void write_file_atomically(const std::filesystem::path& path, const std::function<void(std::ostream&)>& fill) {
  const std::filesystem::path tmp = temporary_name(path);
  auto discard = [&tmp] {
    std::error_code ignored;
    std::filesystem::remove(tmp, ignored);
  };
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw std::runtime_error(path.string() + ": cannot create a temporary file in its folder");
    try {
      fill(out);
      out.flush();
    } catch (...) {
      out.close();
      discard();
      throw;
    }
    if (!out) {
      out.close();
      discard();
      throw std::runtime_error(path.string() + ": write failed (disk full?)");
    }
    out.close();
    if (!out) {
      discard();
      throw std::runtime_error(path.string() + ": write failed while closing");
    }
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) {
    discard();
    throw std::runtime_error(path.string() + ": cannot move the finished file into place: " + ec.message());
  }
}

}  // namespace performer::detail
