#pragma once

#include <string>

#include "imageio/image.h"

namespace imageio {

// Writes an image; the format follows the file extension (".pfm" any case
// with our own PFM writer; ".pbm", ".pgm", ".ppm", ".pnm" any case with our own
// PNM writer, which stores raw P5/P6 with maxval 2^bits_per_sample - 1 and
// refuses float and signed images (see imageio/pnm.h); everything else through
// OpenImageIO).
//
// Integer images are stored as 8-bit samples when bits_per_sample <= 8 and as
// 16-bit samples up to 16; their values must be integers in the range of
// bits_per_sample. A format that cannot hold those samples exactly (e.g.
// signed samples in PNG, 16-bit samples in BMP) is an IoError rather than a
// silent conversion. Float images are written as float where the format
// supports it, otherwise OpenImageIO converts them (0..1 maps to full range).
//
// Atomic: the data goes to a temporary file next to `path` that is renamed
// over it at the end, so a failed write never leaves a partial output file.
void write_image(const std::string& path, const Image& image);

}  // namespace imageio
