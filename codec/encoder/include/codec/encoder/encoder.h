#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "codec/encoder/params.h"
#include "codec/encoder/source_image.h"

namespace codec {

enum class FileFormat { Codestream, Jp2 };

// What an encode tells its caller besides the bytes.
struct EncodeReport {
  std::string dwt_backend;             // the backend that ran the DWT, with its renderer for the GPU
  std::vector<std::string> notices;    // one line each, e.g. the GPU fallback
  std::vector<double> layer_estimates; // per layer: estimated PSNR (dB) from the rate-distortion data
};

// Encodes an image to a JPEG 2000 codestream (.j2k) or a JP2 file. Throws EncodeError.
std::vector<std::uint8_t> encode(const SourceImage& image, const EncodeParams& params, FileFormat format,
                                 EncodeReport* report = nullptr);

}  // namespace codec
