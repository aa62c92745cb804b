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

GridResolution resolution_of(const codec::GridResolution& r) { return GridResolution{r.vertical, r.horizontal}; }

DecodedImage to_public(codec::DecodedImage&& image) {
  DecodedImage out;
  out.x0 = image.x0;
  out.y0 = image.y0;
  out.x1 = image.x1;
  out.y1 = image.y1;
  out.colour_space = image.jp2_colour_space;
  out.icc_profile = std::move(image.icc_profile);
  out.capture_resolution = resolution_of(image.capture_resolution);
  out.display_resolution = resolution_of(image.display_resolution);
  out.warnings = std::move(image.warnings);
  for (codec::DecodedComponent& c : image.components) {
    DecodedComponent d;
    static_cast<ComponentInfo&>(d) = info_of(c);
    d.samples = std::move(c.samples);
    d.wide_samples = std::move(c.wide_samples);
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
      return c.precision <= 31;  // deeper components come as int64 rows (the decoder refuses them here)
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

// decode_into's rows, straight into the caller's buffer as the decoder finishes them (the image
// is never held as int32 planes): the image checked against the view first, then each sample
// converted to the view's type.
class BufferSink : public codec::SampleSink {
 public:
  BufferSink(const OutputView& out, const detail::BufferLayout& layout) : out_(out), layout_(layout) {}

  void begin(const codec::DecodedImage& image) override {
    if (static_cast<int>(image.components.size()) != out_.components)
      throw Error("the image has " + std::to_string(image.components.size()) + " components, the output buffer " +
                  std::to_string(out_.components));
    for (std::size_t c = 0; c < image.components.size(); ++c) {
      const codec::DecodedComponent& comp = image.components[c];
      if (comp.width != out_.width || comp.height != out_.height)
        throw Error("component " + std::to_string(c) + " is " + describe(comp) + ", the output buffer " +
                    std::to_string(out_.width) + "x" + std::to_string(out_.height));
      if (!fits(out_.type, comp))
        throw Error("component " + std::to_string(c) + " is " + describe(comp) + ": its samples do not fit " +
                    type_name(out_.type));
    }
  }

  void put_row(std::size_t component, std::size_t x, std::size_t y, std::span<const std::int32_t> samples) override {
    std::uint8_t* d = static_cast<std::uint8_t*>(out_.data) + component * layout_.component_step +
                      y * layout_.row_stride + x * layout_.pixel_step;
    switch (out_.type) {
      case SampleType::UInt8:
        store<std::uint8_t>(samples, d);
        break;
      case SampleType::UInt16:
        store<std::uint16_t>(samples, d);
        break;
      case SampleType::Int16:
        store<std::int16_t>(samples, d);
        break;
      case SampleType::Int32:
        store<std::int32_t>(samples, d);
        break;
    }
  }

 private:
  // The samples as T, one pixel step apart (begin checked that they fit T).
  template <class T>
  void store(std::span<const std::int32_t> samples, std::uint8_t* d) const {
    for (const std::int32_t v : samples) {
      const auto t = static_cast<T>(v);
      std::memcpy(d, &t, sizeof t);
      d += layout_.pixel_step;
    }
  }

  const OutputView& out_;
  const detail::BufferLayout& layout_;
};

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
    out.icc_profile = header.icc_profile;
    out.capture_resolution = resolution_of(header.capture_resolution);
    out.display_resolution = resolution_of(header.display_resolution);
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
    BufferSink sink(out, layout);
    codec::DecodeReport codec_report;
    codec::DecodedImage image =
        codec::decode_to(bytes_of(data, size), sink, to_codec(options), report ? &codec_report : nullptr);
    if (report) fill_report(codec_report, 0, *report);
    return std::move(image.warnings);
  });
}

}  // namespace gpuj2k
