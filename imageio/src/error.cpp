#include "imageio/error.h"

#include "base/one_line.h"

namespace imageio {

IoError::IoError(const std::string& path, const std::string& problem)
    : std::runtime_error(base::one_line(path + ": " + problem)), path_(path) {}

}  // namespace imageio
