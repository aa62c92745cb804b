#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "imageio/plane_memory.h"

namespace imageio {
struct Image;
struct PlanarImage;
}

namespace codec {

// One image component as the encoder takes it: integer samples at full resolution.
struct SourceComponent {
  int precision = 8;       // bits per sample, 1..16 here (the standard allows up to 38)
  bool is_signed = false;
  imageio::SamplePlane samples;  // row-major, width * height (written in full before it is read)
};

struct SourceImage {
  int width = 0, height = 0;
  std::vector<SourceComponent> components;
};

// Converts a decoded file to components, keeping its precision. Float images and sample types
// beyond 16 bits are refused with an EncodeError naming `path`.
SourceImage to_source_image(const imageio::Image& image, const std::string& path);
// The same checks; the planes are moved, not copied.
SourceImage to_source_image(imageio::PlanarImage&& image, const std::string& path);

}  // namespace codec
