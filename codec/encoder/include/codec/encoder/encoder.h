#pragma once
#include <cstdint>
#include <vector>

#include "codec/encoder/params.h"
#include "codec/encoder/source_image.h"

namespace codec {

enum class FileFormat { Codestream, Jp2 };

// Encodes an image to a JPEG 2000 codestream (.j2k) or a JP2 file. Throws EncodeError.
std::vector<std::uint8_t> encode(const SourceImage& image, const EncodeParams& params, FileFormat format);

}  // namespace codec
