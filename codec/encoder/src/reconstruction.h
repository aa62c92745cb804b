#pragma once
#include <vector>

#include "codec/encoder/params.h"
#include "codec/encoder/source_image.h"
#include "tile_coder.h"

namespace codec {

// Squared error, summed over every sample of every component, of the image a decoder rebuilds
// when it receives `passes[t][b][layer]` coding passes of block b of tile t: dequantisation at the
// interval mid-points, inverse 9/7, inverse ICT, level shift, rounding and clipping to the sample
// range. Blocks are rebuilt on `pool`. This is the true error, where rate control's per-block sums only estimate it
// (the 9/7 is not orthogonal, and truncation errors of neighbouring coefficients correlate).
double rebuilt_squared_error(const SourceImage& image, const CodingPlan& plan, const EncodeParams& params,
                             const std::vector<CodedTile>& tiles,
                             const std::vector<std::vector<std::vector<int>>>& passes, int layer, dwt::DwtBackend& dwt,
                             base::ThreadPool& pool);

}  // namespace codec
