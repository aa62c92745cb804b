#pragma once
#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "codec/dwt_choice/dwt_device.h"  // DwtDevice
#include "codec/structure/grid_resolution.h"
#include "codec/t1/block_style.h"

namespace codec {

enum class Progression { LRCP = 0, RLCP = 1, RPCL = 2, PCRL = 3, CPRL = 4 };

// One quality layer's target. Exactly one kind is used per encode.
struct LayerTarget {
  enum class Kind { Bytes, Psnr } kind = Kind::Bytes;
  double value = 0;  // bytes of the whole file, or PSNR in dB
};

class EncodeEngine;

struct EncodeParams {
  bool lossless = true;  // reversible 5/3 + RCT; otherwise irreversible 9/7 + ICT
  DwtDevice dwt = DwtDevice::Auto;
  // Lossy: quantisation step of the image-domain error, relative to the sample range 2^precision;
  // each subband's step is this divided by its synthesis norm, so every band costs the same
  // squared error per unit of index error and rate control compares them directly.
  double base_step = 1.0 / 2048;
  // Lossy: quality layers, increasing. Empty: one layer keeping every coded pass.
  std::vector<LayerTarget> layers;
  int levels = 5;                                // decomposition levels NL (0..32)
  std::int64_t image_x0 = 0, image_y0 = 0;       // XOsiz, YOsiz: where the image sits on the reference grid
  std::int64_t tile_width = 0, tile_height = 0;  // 0: one tile covering the image
  std::int64_t tile_x0 = 0, tile_y0 = 0;         // XTOsiz, YTOsiz
  int codeblock_width = 64, codeblock_height = 64;
  // Precinct sizes, finest resolution first (opj_compress' and Kakadu's convention); the last entry
  // is halved for each further, coarser resolution. Empty: maximal precincts.
  std::vector<std::pair<int, int>> precincts;
  Progression order = Progression::LRCP;
  bool sop = false, eph = false;
  t1::BlockStyle block_style{};
  // HT block coding (ITU-T T.814 | ISO/IEC 15444-15) for every code-block instead of EBCOT: the
  // codestream gets a CAP marker (Ccap15), Rsiz bit 14 and the HT code-block style bit. Each block
  // is coded by one cleanup pass: on bit-plane 0 without a target; with one (a single layer only),
  // from the plane rate control picks per block. The EBCOT mode switches (block_style) do not apply.
  bool ht = false;
  // HT under a target: each candidate cleanup on plane p >= 1 is followed by SigProp and MagRef
  // passes on p - 1, which rate control may keep (finer truncation points, better quality at a
  // byte count). false: cleanups only, for decoders that read no HT refinement segment (Grok 10).
  bool ht_refinement = true;
  // HT under a byte target, one tile: base_step is moved by up to half an octave, so that the
  // octave's phase puts one of every block's planes at the step a uniform quantiser would take to
  // spend the target (README, "The step's phase"). false keeps base_step as it is given.
  bool ht_step_from_target = true;
  int guard_bits = -1;  // -1: 2 for lossless, 1 for lossy
  int threads = 0;      // 0: all hardware threads
  // Byte and PSNR targets: tier-1 stops coding a block once its bit-planes fall far below the
  // predicted final slope threshold (README, "Pass skipping"). false codes every pass of every block.
  bool skip_passes = true;
  std::string comment = "Created by gpuj2k";
  // JP2 and JPH files: a resolution box with these capture and display resolutions (points per
  // metre of the reference grid), each where given. Codestreams have no place for them.
  GridResolution capture_resolution, display_resolution;
  // Called as code-blocks finish tier-1, from any worker thread (the callee must be thread-safe):
  // blocks done so far and the image's total.
  std::function<void(std::size_t done, std::size_t total)> progress;
  // Worker threads and GPU contexts shared with other encodes (engine.h); `threads` is then the
  // engine's. Null: this encode makes its own and drops them when it ends.
  EncodeEngine* engine = nullptr;
};

// Throws EncodeError for values the standard or this encoder cannot take (code-block sizes that are
// not powers of two from 4 to 1024 with w*h <= 4096, precincts that are not powers of two, ...).
void validate(const EncodeParams& params);

}  // namespace codec
