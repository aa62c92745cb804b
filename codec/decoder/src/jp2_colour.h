#pragma once
#include "codec/decoder/decoder.h"
#include "jp2_reader.h"

namespace codec::dec {

// The JP2 layer above the codestream decoder (T.800 I.5.3): the channels a JP2 reader shows,
// made from the decoded components. In order: the component mapping (cmap) with its palette
// (pclr) turns components into channels; the channel definitions (cdef) put the colour channels
// in the colour space's order (opacity and unspecified channels after them); and, when
// `to_srgb`, sYCC (EnumCS 18) becomes sRGB, chroma upsampled to the luma grid.
// Throws DecodeError for boxes that name components or channels the image lacks.
void apply_jp2_channels(const Jp2File& jp2, bool to_srgb, DecodedImage& image);

}  // namespace codec::dec
