#pragma once

#include <cstdint>
#include <span>
#include <string>

#include "imageio/image.h"

namespace imageio {

// Portable Float Map: "PF" (3 channels) or "Pf" (1 channel), float samples,
// rows stored bottom-to-top. Images returned here are top-row-first like
// every other Image; the flip happens inside.

// Parses a complete PFM file held in memory. Kept separate from file access
// so the parser can be fuzzed directly. `name_for_errors` is the PATH part of
// any IoError thrown.
Image parse_pfm(std::span<const std::uint8_t> bytes, const std::string& name_for_errors);

Image read_pfm(const std::string& path);

// Writes little-endian (scale -1.0). Only 1- and 3-channel images can be
// stored. Atomic: on failure no file (and no partial file) is left at `path`.
void write_pfm(const std::string& path, const Image& image);

}  // namespace imageio
