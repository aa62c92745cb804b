#pragma once
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "codec/t1/block_style.h"

namespace codec {

enum class Progression { LRCP = 0, RLCP = 1, RPCL = 2, PCRL = 3, CPRL = 4 };

struct EncodeParams {
  bool lossless = true;               // reversible 5/3 + RCT; the lossy path arrives with issue 4
  int levels = 5;                     // decomposition levels NL (0..32)
  std::int64_t image_x0 = 0, image_y0 = 0;  // XOsiz, YOsiz: where the image sits on the reference grid
  std::int64_t tile_width = 0, tile_height = 0;  // 0: one tile covering the image
  std::int64_t tile_x0 = 0, tile_y0 = 0;         // XTOsiz, YTOsiz
  int codeblock_width = 64, codeblock_height = 64;
  // Precinct sizes, finest resolution first (opj_compress' and Kakadu's convention); the last entry
  // is halved for each further, coarser resolution. Empty: maximal precincts.
  std::vector<std::pair<int, int>> precincts;
  Progression order = Progression::LRCP;
  bool sop = false, eph = false;
  t1::BlockStyle block_style{};
  int guard_bits = 2;
  int threads = 0;                    // 0: all hardware threads
  std::string comment = "Created by gpuj2k";
};

// Throws EncodeError for values the standard or this encoder cannot take (code-block sizes that are
// not powers of two from 4 to 1024 with w*h <= 4096, precincts that are not powers of two, ...).
void validate(const EncodeParams& params);

}  // namespace codec
