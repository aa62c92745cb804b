#pragma once

#include <string>

#include "imageio/image.h"

namespace imageio::detail {

// The OpenImageIO reader and writer. They live in the OpenImageIO module, a shared object the
// programs load only when a file needs it (see oiio_module.h); read_image and write_image reach
// them through that module. Errors are IoError(path, ...).
Image read_with_oiio(const std::string& path);
void write_with_oiio(const std::string& path, const Image& image);

}  // namespace imageio::detail
