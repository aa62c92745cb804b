#include "gpuj2k/decoder.h"

#include <cstring>
#include <fstream>
#include <iterator>
#include <chrono>
#include <memory>
#include <span>

#include "buffer_layout.h"
#include "library_error.h"
#include "codec/decoder/decoder.h"

namespace gpuj2k {
namespace {

std::span<const std::uint8_t> bytes_of(const void* data, std::size_t size) {
  if (data == nullptr && size > 0) throw Error("stream data is null");
  return {static_cast<const std::uint8_t*>(data), size};
}

codec::DecodeOptions to_codec(const DecodeOptions& o) {
  if (o.reduce < 0 || o.reduce > 32) throw Error("reduce " + std::to_string(o.reduce) + " is outside 0..32");
  if (o.layers < 0) throw Error("layers must not be negative, got " + std::to_string(o.layers));
  if (o.threads < 0) throw Error("threads must not be negative, got " + std::to_string(o.threads));
  if (o.max_memory == 0) throw Error("max_memory must be positive");
  codec::DecodeOptions c;
  c.reduce = o.reduce;
  c.max_layers = o.layers;
  c.components = o.components;
  if (o.region) {
    const Region& r = *o.region;
    if (r.width <= 0 || r.height <= 0)
      throw Error("region size " + std::to_string(r.width) + "x" + std::to_string(r.height) + " is empty or negative");
    c.region = codec::DecodeRegion{r.x, r.y, r.x + r.width, r.y + r.height};
  }
  c.max_memory = o.max_memory;
  c.threads = o.threads;
  c.jp2_sycc_to_srgb = o.sycc_to_srgb;
  c.dwt = o.dwt == DwtDevice::Cpu   ? codec::DwtDevice::Cpu
          : o.dwt == DwtDevice::Gpu ? codec::DwtDevice::Gpu
                                    : codec::DwtDevice::Auto;
  return c;
}

ComponentInfo info_of(const codec::DecodedComponent& c) {
  ComponentInfo out;
  out.width = c.width;
  out.height = c.height;
  out.x0 = c.x0;
  out.y0 = c.y0;
  out.dx = c.dx;
  out.dy = c.dy;
  out.precision = c.precision;
  out.is_signed = c.is_signed;
  return out;
}

void fill_report(const codec::DecodeReport& r, double read_ms, DecodeReport& out) {
  out.threads = r.threads;
  out.dwt_backend = r.dwt_backend;
  out.dwt_reason = r.dwt_reason;
  out.read_ms = read_ms;
  out.parse_ms = r.times.parse;
  out.setup_ms = r.times.setup;
  out.gl_context_ms = r.times.gl_context;
  out.shader_compile_ms = r.times.shader_compile;
  out.tier2_ms = r.times.tier2;
  out.tier1_ms = r.times.tier1;
  out.upload_ms = r.times.upload;
  out.dwt_ms = r.times.dwt;
  out.download_ms = r.times.download;
  out.component_transform_ms = r.times.component_transform;
}

// The decode itself, with the inverse 9/7 where options.dwt chooses (codec/dwt_choice).
codec::DecodedImage run_decode(std::span<const std::uint8_t> bytes, const DecodeOptions& options, DecodeReport* report,
                               double read_ms = 0) {
  codec::DecodeReport codec_report;
  codec::DecodedImage image = codec::decode(bytes, to_codec(options), report ? &codec_report : nullptr);
  if (report) fill_report(codec_report, read_ms, *report);
  return image;
}

DecodedImage to_public(codec::DecodedImage&& image) {
  DecodedImage out;
  out.x0 = image.x0;
  out.y0 = image.y0;
  out.x1 = image.x1;
  out.y1 = image.y1;
  out.colour_space = image.jp2_colour_space;
  out.warnings = std::move(image.warnings);
  for (codec::DecodedComponent& c : image.components) {
    DecodedComponent d;
    static_cast<ComponentInfo&>(d) = info_of(c);
    d.samples = std::move(c.samples);
    out.components.push_back(std::move(d));
  }
  return out;
}

// Whether every sample of a component fits the type, from its declared precision.
bool fits(SampleType type, const codec::DecodedComponent& c) {
  switch (type) {
    case SampleType::UInt8:
      return !c.is_signed && c.precision <= 8;
    case SampleType::UInt16:
      return !c.is_signed && c.precision <= 16;
    case SampleType::Int16:
      return c.is_signed ? c.precision <= 16 : c.precision <= 15;
    case SampleType::Int32:
      return true;
  }
  return false;
}

const char* type_name(SampleType type) {
  switch (type) {
    case SampleType::UInt8:
      return "uint8";
    case SampleType::UInt16:
      return "uint16";
    case SampleType::Int16:
      return "int16";
    case SampleType::Int32:
      return "int32";
  }
  return "?";
}

std::string describe(const codec::DecodedComponent& c) {
  return std::to_string(c.width) + "x" + std::to_string(c.height) + " " + std::to_string(c.precision) + "-bit " +
         (c.is_signed ? "signed" : "unsigned");
}

void write_samples(const codec::DecodedImage& image, const OutputView& out, const detail::BufferLayout& layout) {
  auto* base = static_cast<std::uint8_t*>(out.data);
  for (std::size_t c = 0; c < image.components.size(); ++c) {
    const codec::DecodedComponent& comp = image.components[c];
    for (int y = 0; y < comp.height; ++y) {
      std::uint8_t* row = base + c * layout.component_step + static_cast<std::size_t>(y) * layout.row_stride;
      const std::int32_t* src =
          comp.samples.data() + static_cast<std::size_t>(y) * static_cast<std::size_t>(comp.width);
      for (int x = 0; x < comp.width; ++x) {
        std::uint8_t* d = row + static_cast<std::size_t>(x) * layout.pixel_step;
        const std::int32_t v = src[x];
        switch (out.type) {
          case SampleType::UInt8:
            *d = static_cast<std::uint8_t>(v);
            break;
          case SampleType::UInt16: {
            const auto u = static_cast<std::uint16_t>(v);
            std::memcpy(d, &u, 2);
            break;
          }
          case SampleType::Int16: {
            const auto i = static_cast<std::int16_t>(v);
            std::memcpy(d, &i, 2);
            break;
          }
          case SampleType::Int32:
            std::memcpy(d, &v, 4);
            break;
        }
      }
    }
  }
}

std::vector<std::uint8_t> read_whole_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path + ": cannot open the file");
  std::vector<std::uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) throw Error(path + ": cannot read the file");
  return bytes;
}

}  // namespace

ImageInfo read_info(const void* data, std::size_t size, const DecodeOptions& options) {
  return detail::as_library_error("", [&] {
    const codec::DecodedImage header = codec::read_header(bytes_of(data, size), to_codec(options));
    ImageInfo out;
    out.x0 = header.x0;
    out.y0 = header.y0;
    out.x1 = header.x1;
    out.y1 = header.y1;
    out.colour_space = header.jp2_colour_space;
    for (const codec::DecodedComponent& c : header.components) out.components.push_back(info_of(c));
    return out;
  });
}

DecodedImage decode(const void* data, std::size_t size, const DecodeOptions& options, DecodeReport* report) {
  return detail::as_library_error("", [&] { return to_public(run_decode(bytes_of(data, size), options, report)); });
}

DecodedImage decode_file(const std::string& path, const DecodeOptions& options, DecodeReport* report) {
  const auto read_start = std::chrono::steady_clock::now();
  const std::vector<std::uint8_t> bytes = read_whole_file(path);
  const double read_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - read_start).count();
  return detail::as_library_error(path + ": ", [&] { return to_public(run_decode(bytes, options, report, read_ms)); });
}

std::vector<std::string> decode_into(const void* data, std::size_t size, const OutputView& out,
                                     const DecodeOptions& options, DecodeReport* report) {
  return detail::as_library_error("", [&] {
    if (out.data == nullptr) throw Error("output data is null");
    const detail::BufferLayout layout = detail::check_buffer(
        {out.width, out.height, out.components, out.type, out.layout, out.row_stride, out.plane_stride, out.size_bytes},
        "output buffer");
    codec::DecodedImage image = run_decode(bytes_of(data, size), options, report);
    if (static_cast<int>(image.components.size()) != out.components)
      throw Error("the image has " + std::to_string(image.components.size()) + " components, the output buffer " +
                  std::to_string(out.components));
    for (std::size_t c = 0; c < image.components.size(); ++c) {
      const codec::DecodedComponent& comp = image.components[c];
      if (comp.width != out.width || comp.height != out.height)
        throw Error("component " + std::to_string(c) + " is " + describe(comp) + ", the output buffer " +
                    std::to_string(out.width) + "x" + std::to_string(out.height));
      if (!fits(out.type, comp))
        throw Error("component " + std::to_string(c) + " is " + describe(comp) + ": its samples do not fit " +
                    type_name(out.type));
    }
    write_samples(image, out, layout);
    return std::move(image.warnings);
  });
}

}  // namespace gpuj2k
