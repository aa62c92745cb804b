#include "codec/encoder/params.h"

#include <string>

#include "codec/structure/error.h"

namespace codec {
namespace {

bool power_of_two(std::int64_t v) { return v > 0 && (v & (v - 1)) == 0; }

}  // namespace

void validate(const EncodeParams& p) {
  if (!p.lossless && !(p.base_step > 0 && p.base_step <= 1)) throw EncodeError("the base step must be in (0, 1]");
  if (p.lossless && !p.layers.empty())
    throw EncodeError("rate and quality targets need lossy coding (lossless is set)");
  for (std::size_t i = 0; i < p.layers.size(); ++i) {
    if (!(p.layers[i].value > 0)) throw EncodeError("layer targets must be positive");
    if (p.layers[i].kind != p.layers[0].kind) throw EncodeError("layer targets must all be of one kind");
    if (i > 0 && p.layers[i].value <= p.layers[i - 1].value) throw EncodeError("layer targets must increase");
  }
  if (p.ht && p.layers.size() > 1)
    throw EncodeError(
        "HT coding takes one quality layer: each HT code-block is one cleanup pass, which cannot be "
        "split between layers (give one byte or PSNR target)");
  if (p.ht && p.block_style != t1::BlockStyle{})
    throw EncodeError("--modes are EBCOT's code-block switches; HT code-blocks (--ht) take none of them");
  if (p.layers.size() > 65535) throw EncodeError("at most 65535 quality layers");
  if (p.levels < 0 || p.levels > 32) throw EncodeError("decomposition levels must be between 0 and 32");
  const int w = p.codeblock_width, h = p.codeblock_height;
  if (!power_of_two(w) || !power_of_two(h) || w < 4 || h < 4 || w > 1024 || h > 1024 || w * h > 4096)
    throw EncodeError(
        "code-block " + std::to_string(w) + "x" + std::to_string(h) +
        " is not allowed: width and height must be powers of two from 4 to 1024 with width*height <= 4096 "
        "(T.800 A.6.1)");
  for (const auto& [pw, ph] : p.precincts)
    if (!power_of_two(pw) || !power_of_two(ph) || pw > 32768 || ph > 32768)
      throw EncodeError("precinct " + std::to_string(pw) + "x" + std::to_string(ph) +
                        " is not allowed: sizes must be powers of two up to 32768");
  if (p.image_x0 < 0 || p.image_y0 < 0 || p.tile_x0 < 0 || p.tile_y0 < 0)
    throw EncodeError("image and tile origins must be non-negative");
  if (p.tile_width < 0 || p.tile_height < 0) throw EncodeError("tile sizes must be positive");
  if (p.guard_bits < -1 || p.guard_bits > 7) throw EncodeError("guard bits must be between 0 and 7");
  if (p.threads < 0) throw EncodeError("the thread count must not be negative");
}

}  // namespace codec
