#pragma once
#include <cstdint>
#include <vector>

#include "codec/encoder/params.h"
#include "codec/encoder/source_image.h"
#include "codec/structure/tile.h"
#include "codec/t1/block_encoder.h"
#include "dwt/backend.h"
#include "dwt_cpu/thread_pool.h"

namespace codec {

// Per component quantisation (T.800 E.1). Reversible: no step, one exponent per subband
// (epsilon_b = component precision + log2 gain of the band). Irreversible: an expounded step per
// subband, the base step divided by the band's synthesis norm.
struct ComponentQuantization {
  int precision = 8;   // after the component transform (RCT adds a bit to its colour differences)
  int guard_bits = 2;
  // Per subband in QCD order: LL, then HL, LH, HH per level from coarsest to finest.
  std::vector<int> exponents;
  std::vector<int> mantissas;   // irreversible only
  std::vector<double> steps;    // irreversible only: the step the decoder will use
  std::vector<double> norms;    // irreversible only: synthesis norm of the band
  double component_weight = 1;  // image-domain squared error per unit squared error here (ICT)
  int magnitude_bitplanes(int exponent) const { return guard_bits + exponent - 1; }  // Mb, E-2
};

// A tile after the wavelet transform and tier-1: geometry plus each code-block's codeword.
struct CodedTile {
  Tile tile;
  std::vector<t1::EncodedBlock> blocks;  // indexed by CodeBlock::index
  // Image-domain squared error per unit of tier-1 distortion, per block (rate control).
  std::vector<double> block_weights;
  std::vector<int> block_magnitude_bitplanes;  // the Mb each block was coded with
  // Lossy: the quantisation indices of each tile-component in the Mallat layout, kept so the encoder
  // can rebuild what a decoder sees and measure true error (PSNR targets).
  std::vector<std::vector<std::int32_t>> quantized;
  std::vector<int> guard_bits_needed;    // per component: the fewest guard bits its coefficients fit in
};

// The whole image's coding parameters that every tile shares.
struct CodingPlan {
  ImageGrid grid;
  std::vector<ComponentSampling> sampling;
  std::vector<CodingStyle> styles;
  std::vector<ComponentQuantization> quantization;
  bool rct = false;
  bool ict = false;
};

CodingPlan make_plan(const SourceImage& image, const EncodeParams& params);

// DC shift, component transform, DWT (the 9/7 on `dwt`, the reversible 5/3 on `reversible_dwt`,
// which must take integer planes), quantisation and tier-1 for one tile.
struct StageTimes;
CodedTile code_tile(const SourceImage& image, const CodingPlan& plan, const EncodeParams& params, int tile_index,
                    dwt::DwtBackend& dwt, dwt::DwtBackend& reversible_dwt, dwt_cpu::ThreadPool& pool, StageTimes& times,
                    std::size_t progress_base = 0, std::size_t progress_total = 0);

// Code-blocks of the whole image, for progress reports.
std::size_t count_code_blocks(const CodingPlan& plan);

}  // namespace codec
