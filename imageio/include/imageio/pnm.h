#pragma once

#include <cstdint>
#include <memory>
#include <mutex>
#include <span>
#include <string>
#include <vector>

#include "imageio/image.h"
#include "imageio/plane_memory.h"

namespace imageio {

// Netpbm PBM/PGM/PPM, read and written by our own code rather than
// OpenImageIO (whose 2.4 release writes 16-bit PNM as 8-bit and reads 65535
// back as 65534).
//
// Reading accepts P1 (plain bitmap), P2 (plain grey), P3 (plain RGB),
// P4 (raw bitmap), P5 (raw grey) and P6 (raw RGB):
//  - Header fields are separated by any whitespace and may be interleaved
//    with comments ("#" up to the end of the line); one whitespace character
//    (or a comment ending in a line break) ends the header. Plain (ASCII)
//    rasters may contain comments as well, as libnetpbm accepts.
//  - Samples keep the integer values the file stores; they are not rescaled.
//    bits_per_sample is the bit count of maxval (1..16): 255 gives 8, 4095
//    gives 12, 65535 gives 16. A maxval that is not 2^b - 1 (say 1000) still
//    gives the bit count needed to hold it (10), with the samples unchanged,
//    so writing such an image back stores maxval 1023.
//  - 16-bit raw samples (maxval > 255) are big-endian, as Netpbm specifies.
//  - Bitmaps (P1/P4) keep Netpbm's meaning of a bit (1 = black) but are
//    returned as 1-bit grey images, sample = 1 - bit, so that white is 1 and
//    black is 0 just as in a PGM with maxval 1. P4 rows are padded to whole
//    bytes; the padding bits are ignored.
//  - Only the first image is read: Netpbm allows several images in one file,
//    so anything after the first raster is ignored.
//  - Rejected with IoError: bad magic number (including PAM "P7"), missing,
//    non-numeric, zero or negative dimensions, maxval 0 or above 65535,
//    samples above maxval, truncated header or raster, and images of more
//    than 2^31 samples (refused before anything is allocated).

// Parses a complete PNM file held in memory. Kept separate from file access
// so the parser can be fuzzed directly. `name_for_errors` is the PATH part of
// any IoError thrown.
Image parse_pnm(std::span<const std::uint8_t> bytes, const std::string& name_for_errors);

Image read_pnm(const std::string& path);

// The same file, the same checks and errors, as its integer samples. A raw raster with maxval 255
// or 65535 is not copied: parse_pnm_packed's result then points into `bytes`, which must outlive
// it, and read_pnm_packed's keeps the mapped file.
PackedImage parse_pnm_packed(std::span<const std::uint8_t> bytes, const std::string& name_for_errors);
PackedImage read_pnm_packed(const std::string& path);

// Writes a raw PNM: 1 channel as P5, 3 channels as P6, any other channel
// count is an IoError. The file's maxval is 2^bits_per_sample - 1, so samples
// are written unchanged; bits_per_sample must be 1..16, samples unsigned
// integers in that range (float and signed images are an IoError: PNM has
// neither). Samples above 8 bits take two big-endian bytes. The extension is
// not consulted: a 3-channel image written to "x.pgm" is still a P6 file.
// Atomic: on failure no file (and no partial file) is left at `path`.
void write_pnm(const std::string& path, const Image& image);

// A raw PNM file (P5 grey, P6 RGB) made in memory from integer rows put in any order, as a
// decoder finishes them (from several threads at once, each sample once), then written whole: the
// raster is in the file's layout from the start, with no plane per channel in between. Samples
// never put are 0. Errors are IoErrors naming `path`.
class PnmRaster {
 public:
  // width x height pixels of 1 or 3 channels of `bits` (1..16) bits, maxval 2^bits - 1.
  PnmRaster(std::string path, int width, int height, int channels, int bits);
  // Channel c of pixels [x, x + samples.size()) of row y; every sample in 0..maxval.
  void put_row(int channel, std::size_t x, std::size_t y, std::span<const std::int32_t> samples);
  // The three channels of those pixels at once (a 3-channel raster), interleaved vector-wide.
  void put_rgb_row(std::size_t x, std::size_t y, std::span<const std::int32_t> r, std::span<const std::int32_t> g,
                   std::span<const std::int32_t> b);
  // The file, atomically: on failure no file (and no partial file) is left at the path.
  void write();

 private:
  // Checked against the raster; the row is zeroed first if this is its first touch.
  std::uint8_t* pixels_at(std::size_t x, std::size_t y, std::size_t n);
  void clear_row_once(std::size_t y);
  [[noreturn]] void throw_outside(std::span<const std::int32_t> samples, std::size_t x, std::size_t y) const;

  std::string path_;
  std::size_t width_ = 0, height_ = 0, channels_ = 0;
  std::uint32_t maxval_ = 0;
  std::size_t sample_bytes_ = 1, header_bytes_ = 0;
  std::vector<std::uint8_t, UninitialisedAllocator<std::uint8_t>> bytes_;  // the header, then the raster
  // Each row is zeroed when it is first touched, by whichever thread puts into it first (write()
  // zeroes the rows never put), instead of the whole raster in one pass before the decode: that
  // pass was 42 ms of a 4096x4096 RGB decode on one thread, before any row arrived.
  std::unique_ptr<std::once_flag[]> row_cleared_;
};

}  // namespace imageio
