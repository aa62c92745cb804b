#pragma once
#include <cstddef>
#include <string>
#include <vector>

#include "base/thread_pool.h"
#include "codec/decoder/decoder.h"
#include "codec/structure/tile.h"
#include "codestream_reader.h"
#include "dwt/backend.h"
#include "dwt_cpu/cpu_backend.h"

namespace codec::dec {

// What one tile's decode may use: the DWT backends and the memory it may claim.
struct TileDecodeSetup {
  const DecodeOptions* options = nullptr;
  dwt::DwtBackend* reversible_backend = nullptr;    // CPU lifting (exact 5/3)
  dwt::DwtBackend* irreversible_backend = nullptr;  // CPU or GPU 9/7
  dwt_cpu::CpuBackend* wide_backend = nullptr;      // both kernels on 64-bit planes (CPU only)
  std::size_t memory_budget = 0;                    // for this tile's working set
  Rect window;                                      // the part of the image wanted, on the reference grid
  std::vector<bool> selected;                       // per codestream component: output or not
  base::ThreadPool* pool = nullptr;                 // tier-1 runs its code-blocks on it
  DecodeStageTimes* times = nullptr;                // required: each stage's time is added here
  SampleSink* sink = nullptr;                       // where finished rows go; null: the image's components' samples
};

// Bytes one tile's structures and planes would need (an upper bound), so that a hostile header is
// refused before anything is allocated.
double tile_working_set(const Codestream& cs, const TileParams& params, int tile_index, int reduce);

// Decodes one tile, the later stages of the decoder's data flow: tier-2 packets, tier-1 blocks,
// dequantisation, inverse DWT, inverse MCT, level shift and clamping, into the image's components
// (already sized). Problems that leave the tile partly decoded (a truncation) go to `warnings`.
void decode_tile(const Codestream& cs, const TileStream& tile, const TileDecodeSetup& setup, DecodedImage& image);

}  // namespace codec::dec
