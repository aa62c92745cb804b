// Which writer a file goes to: PFM and Netpbm by name to our own, anything else to OpenImageIO.
// The checks come first, so that no writer ever clamps or rounds a sample behind the caller.

#include "imageio/write.h"

#include "file_extension.h"
#include "image_checks.h"
#include "imageio/pfm.h"
#include "imageio/pnm.h"
#include "oiio_module.h"

namespace imageio {

void write_image(const std::string& path, const Image& image) {
  detail::check_layout(path, image);
  if (!image.is_float) detail::check_integer_samples(path, image);
  if (detail::has_pfm_extension(path)) {
    write_pfm(path, image);
    return;
  }
  if (detail::has_pnm_extension(path)) {
    write_pnm(path, image);
    return;
  }
  detail::write_through_module(path, image);
}

}  // namespace imageio
