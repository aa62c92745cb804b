#pragma once
#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

#include "codec/encoder/encoder.h"
#include "codec/encoder/params.h"
#include "codec/encoder/source_image.h"
#include "tile_coder.h"
#include "base/thread_pool.h"

namespace codec {

// Stage 5 of the pipeline (DESIGN.md): which passes of every code-block each quality layer
// carries. passes[t][b][l]: the cumulative passes of block b of tile t after layer l.
using LayerPasses = std::vector<std::vector<std::vector<int>>>;

// Every pass of every block in every layer: the selection without a target.
LayerPasses every_pass(const std::vector<CodedTile>& tiles, int layers);

// The codestream (or file) a selection makes.
using Assembler = std::function<std::vector<std::uint8_t>(const LayerPasses&)>;
// The length of that file, exactly, as rate control's byte targets measure trial selections.
using FileSizer = std::function<std::size_t(const LayerPasses&)>;

// What rate control takes from the encode around it.
struct RateControlInputs {
  const SourceImage& image;  // the source, for PSNR targets (which rebuild the image and compare)
  const CodingPlan& plan;
  const EncodeParams& params;  // params.layers: the targets, one per layer (not empty)
  double samples = 0;          // over every component
  double peak = 255;           // largest sample value, for PSNR
  base::ThreadPool& pool;
};

// PCRD-opt over every block of every tile (one slope threshold per layer) against the layer
// targets: byte targets are met exactly as the assembled file counts them (headers included),
// PSNR targets by measuring the rebuilt image. With pass skipping, blocks the allocation cuts
// within their last coded bit-plane may have stopped too soon: they are coded again in full on
// `pool` (tiles are updated; at most two rounds) and the allocation repeated, which gives the
// selection coding every pass would. Times go to report.times (rate control; recoding as tier-1)
// and the recoded blocks are counted in report.recoded_blocks. HT blocks come with cleanups from
// several planes as their truncation points (ht_rate.h): blocks whose choice lies at the edge of
// those coded get more planes coded between rounds, and at the end each block's chosen cleanup
// takes its place (one pass in `passes`).
LayerPasses control_rate(std::vector<CodedTile>& tiles, const RateControlInputs& in, const FileSizer& file_size,
                         EncodeReport& report);

}  // namespace codec
