#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "imageio/image.h"
#include "imageio/plane_memory.h"

namespace codec {

// One image component as the encoder takes it: integer samples at full resolution.
struct SourceComponent {
  int precision = 8;  // bits per sample, 1..16 here (the standard allows up to 38)
  bool is_signed = false;
  imageio::SamplePlane samples;  // row-major, width * height (written in full before it is read)
};

struct SourceImage {
  int width = 0, height = 0;
  std::vector<SourceComponent> components;
  // Set when the samples are still packed as the file held them (to_source_image(PackedImage&&)):
  // the components' `samples` are then empty, and the stages unpack the rows they work on
  // (source_row), so that no image-sized integer copy is ever made.
  std::shared_ptr<const imageio::PackedImage> packed;
};

// Samples x0 .. x0 + n - 1 of row y of component c: a pointer into the component's plane or, for
// a packed image, into `scratch` (room for n samples), unpacked there.
const std::int32_t* source_row(const SourceImage& image, std::size_t c, std::size_t y, std::size_t x0, std::size_t n,
                               std::int32_t* scratch);

// Converts a decoded file to components, keeping its precision. Float images and sample types
// beyond 16 bits are refused with an EncodeError naming `path`.
SourceImage to_source_image(const imageio::Image& image, const std::string& path);
// The same checks; the samples stay packed (SourceImage::packed), the raster is not copied.
SourceImage to_source_image(imageio::PackedImage&& image, const std::string& path);

}  // namespace codec
