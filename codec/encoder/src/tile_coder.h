#pragma once
#include <cstdint>
#include <limits>
#include <memory>
#include <new>
#include <optional>
#include <span>
#include <type_traits>
#include <utility>
#include <vector>

#include "codec/encoder/params.h"
#include "codec/encoder/source_image.h"
#include "codec/rate/hull.h"
#include "codec/structure/tile.h"
#include "codec/ht/ht_block_encoder.h"
#include "codec/t1/block_encoder.h"
#include "dwt/backend.h"
#include "base/thread_pool.h"
#include "ht_candidates.h"
#include "imageio/plane_memory.h"

namespace codec {

// Per component quantisation (T.800 E.1). Reversible: no step, one exponent per subband
// (epsilon_b = component precision + log2 gain of the band). Irreversible: an expounded step per
// subband, the base step divided by the band's synthesis norm.
struct ComponentQuantization {
  int precision = 8;  // after the component transform (RCT adds a bit to its colour differences)
  int guard_bits = 2;
  // Per subband in QCD order: LL, then HL, LH, HH per level from coarsest to finest.
  std::vector<int> exponents;
  std::vector<int> mantissas;   // irreversible only
  std::vector<double> steps;    // irreversible only: the step the decoder will use
  std::vector<double> norms;    // irreversible only: synthesis norm of the band
  double component_weight = 1;  // image-domain squared error per unit squared error here (ICT)
  int magnitude_bitplanes(int exponent) const { return guard_bits + exponent - 1; }  // Mb, E-2
};

// Planes written in full before they are read start uninitialised (imageio::UninitialisedAllocator):
// their pages are first touched by the stage that fills them, and while a given-up source image is
// released row by row the two never coexist.
using FloatPlane = std::vector<float, imageio::UninitialisedAllocator<float>>;

// One code-block as tier-1 and rate control see it: where its indices lie, its band, its weight.
struct BlockJob {
  std::size_t component = 0;
  std::size_t block_index = 0;  // CodeBlock::index
  int resolution = 0;           // 0: the lowest (LL)
  t1::Orientation orientation = t1::Orientation::LL;
  std::int64_t x0 = 0, y0 = 0;  // in the tile-component's Mallat layout
  int width = 0, height = 0;
  std::int64_t plane_width = 0;
  int exponent = 0;        // the band's epsilon_b
  double weight = 1;       // image-domain squared error per unit of tier-1 distortion (lossy)
  float inverse_step = 1;  // lossy: 1 / the band's quantisation step
  float step = 1;          // lossy: the step itself, as dequantisation uses it
};

// Pass skipping (code_tile_blocks): a sample of the blocks predicts the final slope threshold; the others
// stop once two bit-planes in a row each buy less than that threshold / kStopSafety (a plane's
// slope falls about fourfold from one to the next, so the second quiet plane is the margin), or
// one where the block's slopes behave (t1's stops_after_quiet_plane), and
// are not coded at all when their whole energy for one byte would buy less. The sample is
// stratified by resolution: resolutions of at most kWholeResolutionBlocks blocks whole, one block
// in kSampleStride of the others. Of it, a sparser sample (kPresampleStride) is coded first, in
// full or, at low byte targets, down to an eighth below the floor its top bit-planes predict
// (presample_top_planes in tile_coder.cpp), and the rest stops at the threshold that predicts /
// kPresampleMargin.
// Measured on the 2048x2048 mosaic (planes coded, blocks coded again because they stopped too
// soon), with the unstratified sample of 2026-11-24: safety 4 codes 15980 planes at 3 bpp and
// 10423 at 0.75 bpp; 2 codes 14489 and 10030 with 74 blocks recoded at 0.1875 bpp; 1.4 codes 14096
// and 9392 but recodes 133 blocks at 0.1875 bpp, and 1 changes the 3 bpp file. Stride 8 and
// safety 8 code 15-25 % more than stride 16 and safety 4 for the same files. The stratified sample
// predicts the mosaic's final threshold within 4 % at 0.1875, 0.75 and 3 bpp (the unstratified one
// was 2.7 times too high at 0.1875 bpp), and no block is recoded. With it and the one-plane stop
// (2026-11-25), safety 1.5 codes 7 % fewer instructions than 2 at 3 bpp (2-3 % at 0.1875 and 0.75)
// for the same files on the mosaic and on all 80 Kodak pass-skipping cases.
inline constexpr std::size_t kSampleStride = 16;
inline constexpr std::size_t kPresampleStride = 64;
inline constexpr std::size_t kWholeResolutionBlocks = 16;
inline constexpr double kPresampleMargin = 8;
inline constexpr double kStopSafety = 1.5;

// A tile after the wavelet transform and tier-1: geometry plus each code-block's codeword.
struct CodedTile {
  Tile tile;
  std::vector<t1::EncodedBlock> blocks;        // indexed by CodeBlock::index
  std::vector<int> block_magnitude_bitplanes;  // the Mb each block was coded with
  // Each tile-component's wavelet coefficients in the Mallat layout, kept so that blocks can be
  // coded again (pass skipping) and the encoder can rebuild what a decoder sees (PSNR targets):
  // reversible integers (lossless), or floats that tier-1 quantises as it loads each block (lossy).
  std::vector<imageio::SamplePlane> quantized;
  std::vector<FloatPlane> coefficients;
  std::vector<BlockJob> jobs;          // every block, indexed by CodeBlock::index: where it lies, its weight, its step
  double stop_threshold = 0;           // the StopRule tier-1 ran with; 0: every pass
  std::vector<int> guard_bits_needed;  // per component: the fewest guard bits its coefficients fit in
  // HT under a byte or PSNR target: per block, the cleanups coded from several planes, which
  // `blocks` then holds as truncation points (ht_candidates.h) until rate control settles on one.
  // Empty otherwise.
  std::vector<HtCandidates> ht_candidates;
  // HT under a target: the length model's bytes per model bit, as the sample measured it (ht_rate.cpp).
  double ht_bytes_per_model_bit = 0;
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

struct StageTimes;
// What pass skipping aims at in one tile: its share of the code-block bytes a byte target leaves,
// or of the squared error (image units) a PSNR target allows. None codes every pass.
struct Tier1Target {
  enum class Kind { None, Bytes, Distortion } kind = Kind::None;
  double value = 0;
};

// Stages 1 and 2 of one tile: its samples DC shifted and through the component transform, then
// the DWT (the 9/7 on `dwt`, the reversible 5/3 on `reversible_dwt`, which must take integer
// planes), into coded.coefficients (lossy) or coded.quantized (lossless). `consumable`: the same
// image when the caller gave it up (encode(SourceImage&&)); a lossless tile covering it whole then
// takes its planes instead of copying them. Null otherwise.
CodedTile transform_tile(const SourceImage& image, SourceImage* consumable, const CodingPlan& plan,
                         const EncodeParams& params, int tile_index, dwt::DwtBackend& dwt,
                         dwt::DwtBackend& reversible_dwt, base::ThreadPool& pool, StageTimes& times);

// Stages 3 and 4: quantisation at `plan`'s steps and tier-1 of every code-block of a transformed
// tile, under `target` (pass skipping, or HT's candidates), and its guard bits found.
void code_tile_blocks(CodedTile& coded, const CodingPlan& plan, const EncodeParams& params, base::ThreadPool& pool,
                      StageTimes& times, Tier1Target target = {}, std::size_t progress_base = 0,
                      std::size_t progress_total = 0);

// For an HT byte target: a base step of `plan`'s octave phase moved to where the uniform quantiser
// that spends `target` sits on the block's plane grid (ht_uniform_step_octaves), within half an
// octave of params.base_step. The allocation's choices of whole planes then include, for most
// blocks, that quantiser itself (README, "The step's phase"). Empty when no such step is found.
// `coded`: a transformed tile (its jobs are set to `plan`'s).
std::optional<double> ht_aligned_base_step(CodedTile& coded, const CodingPlan& plan, const EncodeParams& params,
                                           const Tier1Target& target, base::ThreadPool& pool);

// Gives the pages of every tile's kept coefficient planes back to the system, chunks of them on the
// pool's threads at once (imageio::discard_pages), before the planes themselves are freed: on a
// 2-vCPU VM the one munmap of each plane's release had freed a 4096x4096 RGB encode's 192 MiB on
// one thread. The planes' values are gone afterwards (they read as zeros).
void discard_coefficient_planes(std::vector<CodedTile>& tiles, base::ThreadPool& pool);

// Tier-1 of one block of a coded tile, from its kept coefficients.
t1::EncodedBlock code_block(const CodedTile& coded, const BlockJob& job, const EncodeParams& params,
                            int magnitude_bitplanes, t1::StopRule stop = {});

// A code-block loaded for the HT coder from a coded tile's kept coefficients (quantised as loaded),
// into `into`: a block kept from an earlier load needs no allocation or clearing for the same size.
void load_ht_block(const CodedTile& coded, const BlockJob& job, const EncodeParams& params, ht::HtBlock& into);

// A block of a lossy tile's kept coefficients, where they lie in its plane.
t1::FloatBlock float_block(const CodedTile& coded, const BlockJob& job);

// A sample of a tile's code-blocks that stands for all of them: each sampled block with the number
// of blocks' worth of coefficients it represents. Stratified by resolution (see kSampleStride): one
// block in `stride` of each resolution, or fewer where that would take more than `most` blocks of
// one resolution (a prediction's accuracy follows the blocks sampled, not the fraction of them).
struct BlockSample {
  std::vector<std::size_t> blocks;
  std::vector<double> scale;
};
// `scattered`: each block of a resolution taken with probability 1 / stride, by a hash of its place
// in the resolution, rather than one in every `stride` in order, which can fall in step with a
// period of the content (a mosaic's tiles) and over- or under-represent it.
BlockSample sample_blocks(const std::vector<BlockJob>& jobs, std::size_t stride,
                          std::size_t most = std::numeric_limits<std::size_t>::max(), bool scattered = false);

// The slope threshold at which a sample of coded blocks, scaled up, spends the tile's bytes or
// leaves the tile's squared error (`target`), from the blocks' passes as rate control sees them.
double predict_threshold(const std::vector<BlockJob>& jobs, const CodedTile& coded, const BlockSample& sample,
                         const Tier1Target& target);

// The same from any hulls: the slope threshold at which blocks with these hulls, each standing for
// `scale` blocks' worth, spend the target's bytes or leave its squared error; `energy` is their
// weighted energy, scaled alike.
double threshold_for_target(std::span<const std::vector<rate::HullPoint>> hulls, std::span<const double> scale,
                            double energy, const Tier1Target& target);

// Code-blocks of the whole image, for progress reports.
std::size_t count_code_blocks(const CodingPlan& plan);

}  // namespace codec
