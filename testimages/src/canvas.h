#pragma once

#include <cstdint>

namespace testimages::detail {

// What a pattern needs to know to compute one sample. Patterns work on
// unsigned "levels" 0..max_level; generate() shifts them for signed output.
struct Canvas {
  int width = 0;
  int height = 0;
  int channels = 0;
  int bits = 0;
  std::uint32_t max_level = 0;  // 2^bits - 1
  std::uint64_t seed = 0;
};

// One function per pattern: the level of channel c of pixel (x, y).
using LevelFn = std::uint32_t (*)(const Canvas&, int x, int y, int c);

std::uint32_t zoneplate_level(const Canvas& canvas, int x, int y, int c);
std::uint32_t gradient_h_level(const Canvas& canvas, int x, int y, int c);
std::uint32_t gradient_v_level(const Canvas& canvas, int x, int y, int c);
std::uint32_t gradient_diag_level(const Canvas& canvas, int x, int y, int c);
std::uint32_t edges_level(const Canvas& canvas, int x, int y, int c);
std::uint32_t noise_level(const Canvas& canvas, int x, int y, int c);
std::uint32_t mix_level(const Canvas& canvas, int x, int y, int c);

}  // namespace testimages::detail
