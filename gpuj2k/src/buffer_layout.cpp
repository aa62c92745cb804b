#include "buffer_layout.h"

#include <limits>
#include <string>

namespace gpuj2k::detail {

namespace {

// a * b, or an Error naming `what` when it does not fit in size_t.
std::size_t checked_product(std::size_t a, std::size_t b, const char* what) {
  if (a != 0 && b > std::numeric_limits<std::size_t>::max() / a)
    throw Error(std::string(what) + " overflows the address space");
  return a * b;
}

}  // namespace

std::size_t sample_bytes(SampleType type) {
  switch (type) {
    case SampleType::UInt8:
      return 1;
    case SampleType::UInt16:
    case SampleType::Int16:
      return 2;
    case SampleType::Int32:
      return 4;
  }
  throw Error("unknown sample type");
}

BufferLayout check_buffer(const BufferGeometry& g, const char* what) {
  if (g.width <= 0 || g.height <= 0)
    throw Error("image size " + std::to_string(g.width) + "x" + std::to_string(g.height) + " is empty or negative");
  if (g.components < 1 || g.components > 16384)
    throw Error("component count " + std::to_string(g.components) + " is outside 1..16384");
  BufferLayout out;
  out.sample_bytes = sample_bytes(g.type);
  const auto w = static_cast<std::size_t>(g.width), h = static_cast<std::size_t>(g.height),
             nc = static_cast<std::size_t>(g.components);
  const bool planar = g.layout == Layout::Planar;
  out.pixel_step = planar ? out.sample_bytes : checked_product(out.sample_bytes, nc, "a pixel's size");
  const std::size_t tight_row = checked_product(out.pixel_step, w, "a row's size");
  out.row_stride = g.row_stride == 0 ? tight_row : g.row_stride;
  if (out.row_stride < tight_row)
    throw Error("row stride " + std::to_string(out.row_stride) + " is smaller than a row (" +
                std::to_string(tight_row) + " bytes)");
  const std::size_t plane_bytes = checked_product(out.row_stride, h - 1, "the image's size") + tight_row;
  if (planar) {
    out.component_step = g.plane_stride == 0 ? checked_product(out.row_stride, h, "a plane's size") : g.plane_stride;
    if (out.component_step < plane_bytes)
      throw Error("plane stride " + std::to_string(out.component_step) + " is smaller than a plane (" +
                  std::to_string(plane_bytes) + " bytes)");
  } else {
    out.component_step = out.sample_bytes;
  }
  const std::size_t needed =
      planar ? checked_product(out.component_step, nc - 1, "the image's size") + plane_bytes : plane_bytes;
  if (g.size_bytes < needed)
    throw Error(std::string(what) + " of " + std::to_string(g.size_bytes) + " bytes is smaller than the " +
                std::to_string(needed) + " bytes a " + std::to_string(g.width) + "x" + std::to_string(g.height) +
                " image of " + std::to_string(g.components) + " components needs");
  return out;
}

}  // namespace gpuj2k::detail
