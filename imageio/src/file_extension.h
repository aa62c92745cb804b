#pragma once

#include <string>

namespace imageio::detail {

// True when the file name ends in ".pfm" in any letter case; such files are
// handled by our own reader/writer rather than OpenImageIO.
bool has_pfm_extension(const std::string& path);

// True for ".pbm", ".pgm", ".ppm" and ".pnm" in any letter case; Netpbm files
// are handled by our own reader/writer too (see imageio/pnm.h for why).
bool has_pnm_extension(const std::string& path);

}  // namespace imageio::detail
