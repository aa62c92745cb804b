#include "file_extension.h"

#include <cctype>
#include <filesystem>

namespace imageio::detail {
namespace {

std::string lower_case_extension(const std::string& path) {
  std::string extension = std::filesystem::path(path).extension().string();
  for (char& ch : extension) ch = char(std::tolower(static_cast<unsigned char>(ch)));
  return extension;
}

}  // namespace

bool has_pfm_extension(const std::string& path) { return lower_case_extension(path) == ".pfm"; }

bool has_pnm_extension(const std::string& path) {
  const std::string extension = lower_case_extension(path);
  return extension == ".pbm" || extension == ".pgm" || extension == ".ppm" || extension == ".pnm";
}

}  // namespace imageio::detail
