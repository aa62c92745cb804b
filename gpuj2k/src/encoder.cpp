#include "gpuj2k/encoder.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <functional>
#include <limits>

#include "buffer_layout.h"
#include "library_error.h"
#include "codec/encoder/encoder.h"
#include "codec/encoder/engine.h"
#include "codec/structure/error.h"
#include "imageio/atomic_write.h"
#include "imageio/error.h"
#include "imageio/read.h"

#ifndef GPUJ2K_VERSION
#define GPUJ2K_VERSION "0.0.0"
#endif

namespace gpuj2k {

// What an engine holds: the encoder's shared pool and GPU contexts.
struct Engine::State {
  explicit State(int threads) : encode(threads) {}
  codec::EncodeEngine encode;
};

namespace {

using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point t0) { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); }

// Thrown from the progress callback (on a worker thread) when the caller cancels; the thread pool
// carries it back to the encode's caller, which turns it into Error.
struct Cancelled {};

// The image's samples as the codec takes them: one integer plane per component, every value
// checked against the declared bits (a sample out of range is an error, not silently clipped).
codec::SourceImage to_source(const ImageView& v) {
  if (v.data == nullptr) throw Error("image data is null");
  const detail::BufferLayout layout = detail::check_buffer(
      {v.width, v.height, v.components, v.type, v.layout, v.row_stride, v.plane_stride, v.size_bytes}, "image buffer");
  const int max_bits = v.type == SampleType::UInt8 ? 8 : 16;
  const int bits = v.bits == 0 ? max_bits : v.bits;
  if (bits < 1 || bits > max_bits)
    throw Error("bits per sample " + std::to_string(v.bits) + " is outside 1.." + std::to_string(max_bits) +
                " for this sample type");
  const bool is_signed = v.type == SampleType::Int16 || (v.type == SampleType::Int32 && v.is_signed);
  const auto w = static_cast<std::size_t>(v.width), h = static_cast<std::size_t>(v.height),
             nc = static_cast<std::size_t>(v.components);
  const std::int64_t lo = is_signed ? -(std::int64_t{1} << (bits - 1)) : 0;
  const std::int64_t hi = is_signed ? (std::int64_t{1} << (bits - 1)) - 1 : (std::int64_t{1} << bits) - 1;

  codec::SourceImage out;
  out.width = v.width;
  out.height = v.height;
  const auto* base = static_cast<const std::uint8_t*>(v.data);
  for (std::size_t c = 0; c < nc; ++c) {
    codec::SourceComponent comp;
    comp.precision = bits;
    comp.is_signed = is_signed;
    imageio::resize_with_huge_pages(comp.samples, w * h);
    for (std::size_t y = 0; y < h; ++y) {
      const std::uint8_t* row = base + c * layout.component_step + y * layout.row_stride;
      std::int32_t* dst = comp.samples.data() + y * w;
      for (std::size_t x = 0; x < w; ++x) {
        const std::uint8_t* s = row + x * layout.pixel_step;
        std::int64_t value = 0;
        switch (v.type) {
          case SampleType::UInt8:
            value = *s;
            break;
          case SampleType::UInt16: {
            std::uint16_t u;
            std::memcpy(&u, s, 2);
            value = u;
            break;
          }
          case SampleType::Int16: {
            std::int16_t i;
            std::memcpy(&i, s, 2);
            value = i;
            break;
          }
          case SampleType::Int32: {
            std::int32_t i;
            std::memcpy(&i, s, 4);
            value = i;
            break;
          }
        }
        if (value < lo || value > hi)
          throw Error("sample " + std::to_string(value) + " of component " + std::to_string(c) + " at (" +
                      std::to_string(x) + ", " + std::to_string(y) + ") does not fit " + std::to_string(bits) +
                      "-bit " + (is_signed ? "signed" : "unsigned") + " samples");
        dst[x] = static_cast<std::int32_t>(value);
      }
    }
    out.components.push_back(std::move(comp));
  }
  return out;
}

void require_positive(const std::vector<double>& values, const char* what) {
  for (double v : values)
    if (!(v > 0) || !std::isfinite(v))
      throw Error(std::string(what) + " must be positive numbers, got " + std::to_string(v));
}

static_assert(static_cast<int>(Progression::LRCP) == static_cast<int>(codec::Progression::LRCP) &&
                  static_cast<int>(Progression::RLCP) == static_cast<int>(codec::Progression::RLCP) &&
                  static_cast<int>(Progression::RPCL) == static_cast<int>(codec::Progression::RPCL) &&
                  static_cast<int>(Progression::PCRL) == static_cast<int>(codec::Progression::PCRL) &&
                  static_cast<int>(Progression::CPRL) == static_cast<int>(codec::Progression::CPRL),
              "the public progression orders are the codec's");

// The codec's parameters but the targets, which need the image; checked.
codec::EncodeParams base_params(const EncodeOptions& o) {
  const int kinds = !o.rates_bpp.empty() + !o.ratios.empty() + !o.psnr_db.empty() + (o.size_bytes > 0);
  if (kinds > 1) throw Error("give one kind of target: rates, ratios, PSNR or a size");
  if (o.size_bytes < 0 || !std::isfinite(o.size_bytes)) throw Error("the size target must be positive");
  if (o.lossless && kinds > 0) throw Error("rate and quality targets need lossy coding (lossless is set)");
  require_positive(o.rates_bpp, "rates");
  require_positive(o.ratios, "ratios");
  require_positive(o.psnr_db, "PSNR targets");
  codec::EncodeParams p;
  p.lossless = o.lossless;
  p.base_step = o.base_step;
  p.levels = o.levels;
  p.image_x0 = o.image_x0;
  p.image_y0 = o.image_y0;
  p.tile_width = o.tile_width;
  p.tile_height = o.tile_height;
  p.tile_x0 = o.tile_x0;
  p.tile_y0 = o.tile_y0;
  p.codeblock_width = o.codeblock_width;
  p.codeblock_height = o.codeblock_height;
  p.precincts = o.precincts;
  p.order = static_cast<codec::Progression>(static_cast<int>(o.progression));
  p.sop = o.sop;
  p.eph = o.eph;
  p.block_style.bypass = o.modes.bypass;
  p.block_style.reset = o.modes.reset;
  p.block_style.terminate_each_pass = o.modes.terminate_each_pass;
  p.block_style.vertically_causal = o.modes.vertically_causal;
  p.block_style.predictable_termination = o.modes.predictable_termination;
  p.block_style.segmentation_symbols = o.modes.segmentation_symbols;
  p.guard_bits = o.guard_bits;
  p.comment = o.comment;
  p.capture_resolution = codec::GridResolution{o.capture_resolution.vertical, o.capture_resolution.horizontal};
  p.display_resolution = codec::GridResolution{o.display_resolution.vertical, o.display_resolution.horizontal};
  p.threads = o.threads;
  p.engine = o.engine ? &o.engine->state().encode : nullptr;
  p.skip_passes = !o.code_every_pass;
  p.ht = o.ht;
  p.ht_refinement = o.ht_refinement;
  p.ht_step_from_target = o.ht_step_from_target;
  p.dwt = o.dwt == DwtDevice::Cpu   ? codec::DwtDevice::Cpu
          : o.dwt == DwtDevice::Gpu ? codec::DwtDevice::Gpu
                                    : codec::DwtDevice::Auto;
  if (o.progress) {
    auto callback = o.progress;
    p.progress = [callback](std::size_t done, std::size_t total) {
      if (!callback(done, total)) throw Cancelled{};
    };
  }
  codec::validate(p);
  return p;
}

// The whole parameters for one image: byte targets follow from the image's size (bits per pixel
// over all components, as Kakadu's --rate; ratios of the raw size, as OpenJPEG's -r).
codec::EncodeParams to_params(const EncodeOptions& o, const codec::SourceImage& image) {
  codec::EncodeParams p = base_params(o);
  const double pixels = static_cast<double>(image.width) * image.height;
  double raw_bytes = 0;
  for (const codec::SourceComponent& c : image.components) raw_bytes += pixels * c.precision / 8.0;
  auto add_bytes = [&](double bytes) { p.layers.push_back({codec::LayerTarget::Kind::Bytes, std::floor(bytes)}); };
  for (double bpp : o.rates_bpp) add_bytes(bpp * pixels / 8.0);
  std::vector<double> ratios = o.ratios;
  std::sort(ratios.begin(), ratios.end(), std::greater<>());  // largest ratio = smallest layer first
  for (double r : ratios) add_bytes(raw_bytes / r);
  if (o.size_bytes > 0) add_bytes(o.size_bytes);
  for (double db : o.psnr_db) p.layers.push_back({codec::LayerTarget::Kind::Psnr, db});
  codec::validate(p);
  return p;
}

void fill_report(const codec::EncodeReport& r, const codec::SourceImage& image, double read_ms, EncodeReport& out) {
  out.width = image.width;
  out.height = image.height;
  out.components = static_cast<int>(image.components.size());
  out.threads = r.threads;
  out.dwt_backend = r.dwt_backend;
  out.dwt_reason = r.dwt_reason;
  out.notices = r.notices;
  out.read_ms = read_ms;
  out.setup_ms = r.times.setup;
  out.gl_context_ms = r.times.gl_context;
  out.shader_compile_ms = r.times.shader_compile;
  out.level_shift_ms = r.times.level_shift;
  out.upload_ms = r.times.upload;
  out.dwt_ms = r.times.dwt;
  out.download_ms = r.times.download;
  out.tier1_ms = r.times.tier1;
  out.rate_control_ms = r.times.rate_control;
  out.tier2_ms = r.times.tier2;
  out.release_ms = r.times.release;
  out.recoded_blocks = r.recoded_blocks;
}

// Runs `work`, turning every failure into Error; a cancelled progress callback into "encode cancelled".
template <class Work>
auto guarded(Work&& work) -> decltype(work()) {
  return detail::as_library_error("", [&] {
    try {
      return work();
    } catch (const Cancelled&) {
      throw Error("encode cancelled");
    }
  });
}

codec::FileFormat file_format(Format format) {
  switch (format) {
    case Format::Jp2:
      return codec::FileFormat::Jp2;
    case Format::Jph:
      return codec::FileFormat::Jph;
    case Format::Codestream:
      break;
  }
  return codec::FileFormat::Codestream;
}

std::vector<std::uint8_t> encode_source(codec::SourceImage&& image, const EncodeOptions& options, double read_ms,
                                        EncodeReport* report) {
  const codec::EncodeParams params = to_params(options, image);
  codec::EncodeReport codec_report;
  // Given up: the encoder may reuse or release the samples (it keeps the size and components).
  std::vector<std::uint8_t> bytes = codec::encode(std::move(image), params, file_format(options.format), &codec_report);
  if (report) fill_report(codec_report, image, read_ms, *report);
  return bytes;
}

// An image file's samples, and its resolution where the format records one (TIFF, PNG, JPEG, BMP;
// PNM records none).
struct SourceFile {
  codec::SourceImage image;
  GridResolution resolution;
};

SourceFile read_source(const std::string& path) {
  if (auto packed = imageio::read_packed_if_native(path))
    return SourceFile{codec::to_source_image(std::move(*packed), path), {}};
  imageio::Image image = imageio::read_image(path);
  const GridResolution resolution{image.y_pixels_per_metre, image.x_pixels_per_metre};
  return SourceFile{codec::to_source_image(std::move(image), path), resolution};
}

}  // namespace

std::vector<std::uint8_t> encode(const ImageView& image, const EncodeOptions& options, EncodeReport* report) {
  return guarded([&] { return encode_source(to_source(image), options, 0, report); });
}

std::vector<std::uint8_t> encode_file(const std::string& input_path, const EncodeOptions& options,
                                      EncodeReport* report) {
  return guarded([&] {
    base_params(options);  // option errors should not wait for a large image to be read
    const auto start = Clock::now();
    SourceFile file = read_source(input_path);
    EncodeOptions o = options;
    if (!o.capture_resolution.given()) o.capture_resolution = file.resolution;  // for a JP2/JPH resolution box
    return encode_source(std::move(file.image), o, ms_since(start), report);
  });
}

void encode_file(const std::string& input_path, const std::string& output_path, const EncodeOptions& options,
                 EncodeReport* report) {
  const std::vector<std::uint8_t> bytes = encode_file(input_path, options, report);
  guarded([&] { imageio::write_bytes_atomically(output_path, bytes); });
}

Engine::Engine(int threads) : state_(std::make_unique<State>(threads)) {}
Engine::~Engine() = default;
int Engine::threads() const { return state_->encode.pool().size(); }

std::string version() { return GPUJ2K_VERSION; }

}  // namespace gpuj2k
