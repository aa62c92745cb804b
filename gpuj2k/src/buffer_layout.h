#pragma once
// Where each sample of an image lies in a caller's buffer (gpuj2k::ImageView for encoding,
// gpuj2k::OutputView for decoding): the one place that checks a buffer's geometry, so that neither
// direction can read or write past `size_bytes`.
#include <cstddef>
#include <cstdint>

#include "gpuj2k/common.h"

namespace gpuj2k::detail {

struct BufferGeometry {
  int width = 0, height = 0, components = 0;
  SampleType type = SampleType::UInt8;
  Layout layout = Layout::Interleaved;
  std::size_t row_stride = 0;    // 0: tight
  std::size_t plane_stride = 0;  // planar only; 0: height * row stride
  std::size_t size_bytes = 0;
};

// The checked byte offsets of a buffer: sample (c, x, y) is at c * component_step + y * row_stride
// + x * pixel_step.
struct BufferLayout {
  std::size_t sample_bytes = 1;
  std::size_t pixel_step = 0;
  std::size_t row_stride = 0;
  std::size_t component_step = 0;
};

// Checks the geometry (sizes, strides, that the buffer holds every sample) and gives the offsets;
// throws Error naming the problem. `what` names the buffer in messages ("image buffer").
BufferLayout check_buffer(const BufferGeometry& g, const char* what);

std::size_t sample_bytes(SampleType type);

}  // namespace gpuj2k::detail
