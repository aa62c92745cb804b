// Which reader a file goes to: PFM and Netpbm by name to our own, anything else to OpenImageIO.

#include "imageio/read.h"

#include <optional>
#include <string>

#include "file_extension.h"
#include "imageio/pfm.h"
#include "imageio/pnm.h"
#include "oiio_module.h"

namespace imageio {

Image read_image(const std::string& path) {
  if (detail::has_pfm_extension(path)) return read_pfm(path);
  if (detail::has_pnm_extension(path)) return read_pnm(path);
  return detail::read_through_module(path);
}

std::optional<PackedImage> read_packed_if_native(const std::string& path) {
  if (!detail::has_pnm_extension(path)) return std::nullopt;
  return read_pnm_packed(path);
}

Image read_greyscale(const std::string& path) {
  Image image = read_image(path);
  if (image.channels != 1) {
    throw IoError(path, "expected a greyscale image, found " + std::to_string(image.channels) + " channels");
  }
  return image;
}

}  // namespace imageio
