#include "file_extension.h"

#include <cctype>
#include <filesystem>

namespace imageio::detail {

bool has_pfm_extension(const std::string& path) {
  std::string extension = std::filesystem::path(path).extension().string();
  for (char& ch : extension) ch = char(std::tolower(static_cast<unsigned char>(ch)));
  return extension == ".pfm";
}

}  // namespace imageio::detail
