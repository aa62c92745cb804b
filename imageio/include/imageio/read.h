#pragma once

#include <optional>
#include <string>

#include "imageio/image.h"

namespace imageio {

// Reads any image: ".pfm" (any case) with our own PFM reader, ".pbm", ".pgm",
// ".ppm" and ".pnm" (any case, or a Netpbm file under another name) with our
// own PNM reader (imageio/pnm.h), everything else through OpenImageIO. Native
// precision is kept: 8/16-bit integer files give integer values with
// bits_per_sample 8/16 (PNM: the bit count of maxval, 1..16), half/float
// files give is_float.
// Throws IoError for missing, unreadable, truncated or unsupported files.
Image read_image(const std::string& path);

// PNM files (by name, as read_image decides) as their integer samples (PackedImage: a raw file's
// raster is used where it lies), with read_pnm's checks and errors; nothing for any other file,
// which read_image then reads.
std::optional<PackedImage> read_packed_if_native(const std::string& path);

// read_image, but the image must have exactly one channel.
Image read_greyscale(const std::string& path);

}  // namespace imageio
