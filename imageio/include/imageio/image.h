#pragma once

#include <cassert>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "imageio/error.h"

#include "imageio/plane_memory.h"

namespace imageio {

// An image in memory, whatever its file format or sample type.
//
// Samples are stored as float so that one container covers 8/16-bit integer
// and floating-point input, but integer samples keep their native integer
// values (8-bit 0..255, 16-bit 0..65535, signed types as signed) and are
// never normalised: the codec works on the integer values a file stores.
struct Image {
  int width = 0;
  int height = 0;
  int channels = 0;
  // Precision of integer samples: 8 or 16 for images read from most files
  // (PBM/PGM/PPM: the bit count of the file's maxval, 1..16), any of 1..16
  // for generated ones; 32 for float images.
  int bits_per_sample = 0;
  bool is_signed = false;
  bool is_float = false;
  // Row-major, top row first, channels interleaved.
  std::vector<float> pixels;
  // The ICC colour profile the file carries (read through OpenImageIO), or that a writer should
  // embed where the format can carry one (TIFF, PNG, JPEG); empty: none. PNM and PFM have no place
  // for one.
  std::vector<std::uint8_t> icc_profile;
  // Pixels per metre across and down, as the file records them (TIFF, PNG, JPEG, BMP, through
  // OpenImageIO's XResolution, YResolution and ResolutionUnit) or as a writer should; 0: none (a
  // file that gives only an aspect ratio, or PNM).
  double x_pixels_per_metre = 0, y_pixels_per_metre = 0;

  float& at(int x, int y, int c) { return pixels[index(x, y, c)]; }
  float at(int x, int y, int c) const { return pixels[index(x, y, c)]; }

 private:
  std::size_t index(int x, int y, int c) const {
    assert(x >= 0 && x < width && y >= 0 && y < height && c >= 0 && c < channels);
    return (static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x)) *
               static_cast<std::size_t>(channels) +
           static_cast<std::size_t>(c);
  }
};

// Integer samples as a raw PNM holds them: interleaved, 1 byte each (maxval up to 255) or 2 bytes
// big-endian, top row first. What an encoder takes without an image-sized conversion: it unpacks
// the rows it works on. The raster of a raw file with maxval 255 or 65535 is the file's own bytes
// (mapped from the page cache; `storage` keeps them, or the caller's bytes for parse_pnm_packed);
// other files (plain text, bitmaps, other maxvals) are decoded into `storage`. Unsigned, 1..16 bits.
struct PackedImage {
  int width = 0;
  int height = 0;
  int channels = 0;
  int bits_per_sample = 0;
  int bytes_per_sample = 1;  // 1 or 2 (big-endian)
  const std::uint8_t* raster = nullptr;
  std::shared_ptr<const void> storage;

  std::size_t row_bytes() const {
    return static_cast<std::size_t>(width) * static_cast<std::size_t>(channels) *
           static_cast<std::size_t>(bytes_per_sample);
  }
  // Samples x0 .. x0 + n - 1 of `channel` in row y, into out[0 .. n - 1] (unchecked).
  void unpack_row(int channel, int y, int x0, int n, std::int32_t* out) const;
};

}  // namespace imageio
