#include "codec/decoder/decoder.h"

#include <chrono>
#include <cmath>
#include <filesystem>
#include <iterator>
#include <fstream>
#include <memory>
#include <optional>
#include <utility>

#include "base/thread_pool.h"
#include "codec/dwt_choice/dwt_choice.h"
#include "codestream_reader.h"
#include "dwt_cpu/cpu_backend.h"
#include "imageio/plane_memory.h"
#include "jp2_colour.h"
#include "jp2_reader.h"
#include "tile_decoder.h"

namespace codec {

namespace {

using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point t0) { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); }

std::int64_t reduced(std::int64_t v, int r) { return ceil_shift(v, r); }

// The window decoded: the image area, or the region clipped to it (refused when they miss).
Rect decoded_area(const dec::Siz& siz, const DecodeOptions& options) {
  const Rect image = siz.grid.image;
  if (!options.region) return image;
  const DecodeRegion& r = *options.region;
  const Rect window = image.intersect(Rect{r.x0, r.y0, r.x1, r.y1});
  if (r.x0 >= r.x1 || r.y0 >= r.y1 || window.empty())
    throw DecodeError("the region [" + std::to_string(r.x0) + "," + std::to_string(r.x1) + ") x [" +
                      std::to_string(r.y0) + "," + std::to_string(r.y1) + ") is empty or outside the image [" +
                      std::to_string(image.x0) + "," + std::to_string(image.x1) + ") x [" + std::to_string(image.y0) +
                      "," + std::to_string(image.y1) + ")");
  return window;
}

// Which codestream components are output: all, or the selection (each once, each present).
std::vector<bool> selected_components(const dec::Siz& siz, const DecodeOptions& options) {
  std::vector<bool> selected(siz.components.size(), options.components.empty());
  for (const int c : options.components) {
    if (c < 0 || c >= static_cast<int>(siz.components.size()))
      throw DecodeError("component " + std::to_string(c) + " asked for, but the image has " +
                        std::to_string(siz.components.size()));
    if (selected[static_cast<std::size_t>(c)]) throw DecodeError("component " + std::to_string(c) + " asked for twice");
    selected[static_cast<std::size_t>(c)] = true;
  }
  return selected;
}

// The output image, one entry per codestream component: each selected component's part of the
// decoded window on its grid (B-12), reduced, sized before any tile is decoded, and refused if it
// alone exceeds the memory limit; unselected components stay empty.
// Without `with_samples` the components get their geometry only (read_header).
DecodedImage allocate_image(const dec::Siz& siz, const Rect& window, const std::vector<bool>& selected,
                            const DecodeOptions& options, bool with_samples = true) {
  DecodedImage img;
  const int r = options.reduce;
  img.x0 = reduced(window.x0, r);
  img.y0 = reduced(window.y0, r);
  img.x1 = reduced(window.x1, r);
  img.y1 = reduced(window.y1, r);
  double bytes = 0;
  for (std::size_t c = 0; c < siz.components.size(); ++c) {
    if (!selected[c]) continue;
    const Rect area = tile_component_rect(window, siz.components[c].dx, siz.components[c].dy);
    const std::int64_t w = reduced(area.x1, r) - reduced(area.x0, r), h = reduced(area.y1, r) - reduced(area.y0, r);
    const double sample_bytes = siz.components[c].precision > 31 ? sizeof(std::int64_t) : sizeof(std::int32_t);
    bytes += static_cast<double>(w) * static_cast<double>(h) * sample_bytes;
  }
  if (bytes > static_cast<double>(options.max_memory))
    throw DecodeError("the image would need " + std::to_string(static_cast<long long>(bytes / 1048576)) +
                      " MiB, over the memory limit of " + std::to_string(options.max_memory >> 20) + " MiB");
  for (std::size_t c = 0; c < siz.components.size(); ++c) {
    const dec::ComponentSize& size = siz.components[c];
    const Rect area = tile_component_rect(window, size.dx, size.dy);
    DecodedComponent out;
    out.x0 = static_cast<int>(reduced(area.x0, r));
    out.y0 = static_cast<int>(reduced(area.y0, r));
    out.dx = size.dx;
    out.dy = size.dy;
    out.precision = size.precision;
    out.is_signed = size.is_signed;
    if (selected[c]) {
      out.width = static_cast<int>(reduced(area.x1, r) - out.x0);
      out.height = static_cast<int>(reduced(area.y1, r) - out.y0);
      // Huge pages where the system offers them: a 2048x2048 component is 4096 ordinary pages, each
      // faulted in and cleared on its first touch (imageio/plane_memory.h).
      const std::size_t n = static_cast<std::size_t>(out.width) * static_cast<std::size_t>(out.height);
      if (with_samples && size.precision > 31)
        imageio::resize_with_huge_pages(out.wide_samples, n);
      else if (with_samples)
        imageio::resize_with_huge_pages(out.samples, n);
    }
    img.components.push_back(std::move(out));
  }
  return img;
}

// A resolution of the full reference grid on the grid `reduce` levels down: the same area in
// 2^reduce times fewer points.
GridResolution reduced_resolution(const GridResolution& r, int reduce) {
  const double scale = std::ldexp(1.0, -reduce);
  return GridResolution{r.vertical * scale, r.horizontal * scale};
}

// What a JP2 file's header says about the decoded image beyond its samples: the ICC profile and
// the resolutions (the colour space is set where the channels are made).
void take_jp2_metadata(const dec::Jp2File& jp2, int reduce, DecodedImage& image) {
  image.icc_profile = jp2.icc_profile;
  image.capture_resolution = reduced_resolution(jp2.capture_resolution, reduce);
  image.display_resolution = reduced_resolution(jp2.display_resolution, reduce);
}

bool rewrites_channels(const dec::Jp2File& jp2) {
  return !jp2.channel_sources.empty() || !jp2.channel_definitions.empty() || jp2.colour_space == 18;
}

// The file's boxes (JP2, JPH) if it has them, and its codestream's headers, options checked.
struct OpenedStream {
  std::optional<dec::Jp2File> jp2;
  dec::Codestream cs;
};

OpenedStream open_stream(std::span<const std::uint8_t> bytes, const DecodeOptions& options) {
  if (options.reduce < 0 || options.reduce > 32) throw DecodeError("reduce must be in 0..32");
  if (options.max_layers < 0) throw DecodeError("the layer count must not be negative");
  OpenedStream out;
  std::span<const std::uint8_t> stream = bytes;
  std::size_t base = 0;
  if (dec::looks_like_jp2(bytes)) {
    out.jp2 = dec::read_jp2(bytes);
    stream = out.jp2->codestream;
    base = out.jp2->codestream_offset;
  }
  out.cs = dec::read_codestream(stream, base);
  return out;
}

// The selected components in the order asked for.
void select_in_order(DecodedImage& image, const DecodeOptions& options) {
  std::vector<DecodedComponent> chosen;
  for (const int c : options.components) chosen.push_back(std::move(image.components[static_cast<std::size_t>(c)]));
  image.components = std::move(chosen);
}

// The samples the inverse 9/7 will transform, what --dwt auto weighs: every irreversible
// tile-component (at the kept resolution) of the tiles the window reaches, of the components
// output or needed by the component transform. Tile-part headers may change the wavelet, so each
// tile's own parameters are asked.
double irreversible_samples(const dec::Codestream& cs, const Rect& window, const std::vector<bool>& selected,
                            int reduce) {
  double samples = 0;
  for (const dec::TileStream& tile : cs.tiles) {
    const Rect rect = cs.siz.grid.tile_rect(tile.index);
    if (rect.intersect(window).empty()) continue;
    const dec::TileParams params = dec::resolve_tile_params(cs, tile);
    for (std::size_t c = 0; c < params.components.size() && c < selected.size(); ++c) {
      const bool needed = selected[c] || (params.cod.mct == 1 && c < 3);
      if (!needed || params.components[c].coding.reversible) continue;
      const Rect tc = tile_component_rect(rect, cs.siz.components[c].dx, cs.siz.components[c].dy);
      samples += static_cast<double>(reduced(tc.x1, reduce) - reduced(tc.x0, reduce)) *
                 static_cast<double>(reduced(tc.y1, reduce) - reduced(tc.y0, reduce));
    }
  }
  return samples;
}

// The backend of the inverse 9/7 and why: the caller's, none needed (a reversible stream makes no
// GL context), or --dwt's choice as the encoder makes it.
DwtChoice choose_inverse_dwt(const DecodeOptions& options, double samples, base::ThreadPool& pool) {
  if (options.irreversible_backend) {
    DwtChoice caller;
    caller.name = options.irreversible_backend->name();
    caller.reason = "the caller's backend";
    return caller;
  }
  if (samples == 0)
    return cpu_choice(std::make_unique<dwt_cpu::CpuBackend>(pool),
                      "no irreversible tile-component: the reversible 5/3 runs on the CPU");
  DwtChoice choice = choose_dwt(options.dwt, samples, pool);
  if (!choice.backend) throw DecodeError(choice.reason);
  return choice;
}

// The whole file: a regular file in one read of its size (byte by byte through a stream iterator
// took some 15 ms for a 4 MB codestream), anything else (a pipe) as a stream.
std::vector<std::uint8_t> file_bytes(const std::string& path, std::size_t max_memory) {
  std::error_code error;
  if (std::filesystem::is_directory(path, error)) throw DecodeError("is a directory, not a file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw DecodeError("cannot open the file");
  const auto size =
      std::filesystem::is_regular_file(path, error) ? std::filesystem::file_size(path, error) : std::uintmax_t{0};
  if (error || size == 0) {
    std::vector<std::uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (in.bad()) throw DecodeError("cannot read the file");
    return bytes;
  }
  if (size > max_memory)
    throw DecodeError("the file has " + std::to_string(size) + " bytes, over the memory limit of " +
                      std::to_string(max_memory >> 20) + " MiB");
  std::vector<std::uint8_t> bytes(static_cast<std::size_t>(size));
  if (!in.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(size)))
    throw DecodeError("cannot read the file");
  return bytes;
}

}  // namespace

DecodedImage read_header(std::span<const std::uint8_t> bytes, const DecodeOptions& options) {
  const OpenedStream opened = open_stream(bytes, options);
  const Rect window = decoded_area(opened.cs.siz, options);
  DecodedImage image =
      allocate_image(opened.cs.siz, window, selected_components(opened.cs.siz, options), options, false);
  if (!options.components.empty()) select_in_order(image, options);
  if (opened.jp2) {
    image.jp2_colour_space = opened.jp2->colour_space;
    take_jp2_metadata(*opened.jp2, options.reduce, image);
  }
  image.warnings = opened.cs.warnings;
  return image;
}

namespace {

// A decoded image to the sink: its geometry, then every row of every component, on the pool; the
// samples are then released, as decode_to promises.
void hand_over(DecodedImage& image, SampleSink& sink, base::ThreadPool& pool) {
  // The samples move out, so that the image the sink begins with is its geometry alone, uncopied.
  std::vector<std::vector<std::int32_t>> samples;
  std::vector<std::vector<std::int64_t>> wide_samples;
  for (DecodedComponent& comp : image.components) {
    samples.push_back(std::exchange(comp.samples, {}));
    wide_samples.push_back(std::exchange(comp.wide_samples, {}));
  }
  sink.begin(image);
  for (std::size_t c = 0; c < image.components.size(); ++c) {
    const auto width = static_cast<std::size_t>(image.components[c].width);
    const auto height = static_cast<std::size_t>(image.components[c].height);
    if (const std::vector<std::int32_t>& rows = samples[c]; !rows.empty())
      pool.parallel_for(height, [&](std::size_t y) {
        sink.put_row(c, 0, y, std::span<const std::int32_t>(rows.data() + y * width, width));
      });
    if (const std::vector<std::int64_t>& rows = wide_samples[c]; !rows.empty())
      pool.parallel_for(height, [&](std::size_t y) {
        sink.put_row_wide(c, 0, y, std::span<const std::int64_t>(rows.data() + y * width, width));
      });
  }
}

// A sink that takes only 31-bit samples is refused an image with deeper components before anything
// is decoded.
void check_sink_takes(const DecodedImage& image, const SampleSink& sink) {
  if (sink.takes_wide_samples()) return;
  for (const DecodedComponent& comp : image.components)
    if (comp.precision > 31)
      throw DecodeError("a component has " + std::to_string(comp.precision) +
                        " bits, more than this output takes (31)");
}

// The samples of a tile missing from the stream (its part `area` of the window, on the reference
// grid) to the sink as zeros, so that a sink gets every sample once, as the image's own
// components hold zeros there.
void put_zero_rows(const Rect& area, const DecodedImage& image, int reduce, SampleSink& sink) {
  for (std::size_t c = 0; c < image.components.size(); ++c) {
    const DecodedComponent& comp = image.components[c];
    const Rect a = tile_component_rect(area, comp.dx, comp.dy);
    const Rect rows =
        Rect{reduced(a.x0, reduce), reduced(a.y0, reduce), reduced(a.x1, reduce), reduced(a.y1, reduce)}.intersect(
            Rect{comp.x0, comp.y0, std::int64_t{comp.x0} + comp.width, std::int64_t{comp.y0} + comp.height});
    if (rows.empty()) continue;
    const auto x = static_cast<std::size_t>(rows.x0 - comp.x0), n = static_cast<std::size_t>(rows.width());
    const bool wide = comp.precision > 31;
    const std::vector<std::int32_t> zeros(wide ? 0 : n, 0);
    const std::vector<std::int64_t> wide_zeros(wide ? n : 0, 0);
    for (std::int64_t y = rows.y0; y < rows.y1; ++y) {
      const auto row = static_cast<std::size_t>(y - comp.y0);
      if (wide)
        sink.put_row_wide(c, x, row, wide_zeros);
      else
        sink.put_row(c, x, row, zeros);
    }
  }
}

// decode, and decode_to's sink when `sink` is not null.
DecodedImage decode_with(std::span<const std::uint8_t> bytes, const DecodeOptions& options, DecodeReport* report_out,
                         SampleSink* sink) {
  DecodeReport report;
  DecodeStageTimes& times = report.times;
  const auto parse_start = Clock::now();
  const OpenedStream opened = open_stream(bytes, options);
  const std::optional<dec::Jp2File>& jp2 = opened.jp2;
  const dec::Codestream& cs = opened.cs;
  times.parse = ms_since(parse_start);

  // Setup: the output image, one set of worker threads for tier-1 and the CPU DWT, and where the
  // inverse 9/7 runs.
  const auto setup_start = Clock::now();
  const Rect window = decoded_area(cs.siz, options);
  const std::vector<bool> selected = selected_components(cs.siz, options);
  // A sink takes the tiles' rows as they are made, unless the output needs the whole image first.
  const bool rows_to_sink = sink && options.components.empty() && !(jp2 && rewrites_channels(*jp2));
  DecodedImage image = allocate_image(cs.siz, window, selected, options, !rows_to_sink);
  if (sink) check_sink_takes(image, *sink);
  image.warnings = cs.warnings;
  if (jp2) take_jp2_metadata(*jp2, options.reduce, image);
  if (rows_to_sink) {
    if (jp2) image.jp2_colour_space = jp2->colour_space;
    sink->begin(image);
  }
  double image_bytes = 0;
  for (const DecodedComponent& c : image.components)
    image_bytes += static_cast<double>(c.samples.size()) * 4 + static_cast<double>(c.wide_samples.size()) * 8;
  base::ThreadPool pool(options.threads);
  report.threads = pool.size();
  dwt_cpu::CpuBackend cpu(pool);
  DwtChoice dwt = choose_inverse_dwt(options, irreversible_samples(cs, window, selected, options.reduce), pool);
  report.dwt_backend = dwt.name;
  report.dwt_reason = dwt.reason;
  times.gl_context = dwt.gl_context_ms;
  times.shader_compile = dwt.shader_compile_ms;
  dec::TileDecodeSetup setup;
  setup.options = &options;
  setup.pool = &pool;
  setup.reversible_backend = &cpu;
  setup.wide_backend = &cpu;
  setup.irreversible_backend = options.irreversible_backend ? options.irreversible_backend : dwt.backend.get();
  setup.memory_budget = static_cast<std::size_t>(static_cast<double>(options.max_memory) - image_bytes);
  setup.window = window;
  setup.selected = selected;
  setup.times = &times;
  setup.sink = rows_to_sink ? sink : nullptr;
  times.setup = ms_since(setup_start) - times.gl_context - times.shader_compile;

  // Tiles the window misses are neither decoded nor missed.
  std::vector<bool> seen(static_cast<std::size_t>(cs.siz.grid.tile_count()), false);
  for (int t = 0; t < cs.siz.grid.tile_count(); ++t)
    if (cs.siz.grid.tile_rect(t).intersect(window).empty()) seen[static_cast<std::size_t>(t)] = true;
  for (const dec::TileStream& tile : cs.tiles) {
    if (cs.siz.grid.tile_rect(tile.index).intersect(window).empty()) continue;
    dec::decode_tile(cs, tile, setup, image);
    seen[static_cast<std::size_t>(tile.index)] = true;
  }
  int missing = 0;
  for (std::size_t t = 0; t < seen.size(); ++t) {
    if (seen[t]) continue;
    ++missing;
    if (rows_to_sink)
      put_zero_rows(cs.siz.grid.tile_rect(static_cast<int>(t)).intersect(window), image, options.reduce, *sink);
  }
  if (missing > 0)
    image.warnings.push_back(std::to_string(missing) + " of " + std::to_string(seen.size()) +
                             " tile(s) missing from the stream; their samples are 0");
  const auto channels_start = Clock::now();
  if (!options.components.empty()) {
    select_in_order(image, options);
    if (jp2 && rewrites_channels(*jp2))
      image.warnings.push_back(
          "the JP2 palette, channel definitions and colour conversion are not applied to a component selection");
    if (jp2) image.jp2_colour_space = jp2->colour_space;
  } else if (jp2) {
    dec::apply_jp2_channels(*jp2, options.jp2_sycc_to_srgb, image);
  }
  if (sink && !rows_to_sink) hand_over(image, *sink, pool);
  times.component_transform += ms_since(channels_start);
  if (dwt.backend && dwt.backend->device_timings()) {
    const auto teardown_start = Clock::now();
    dwt.backend.reset();  // a GL context's teardown is part of what the context costs
    times.gl_context += ms_since(teardown_start);
  }
  if (report_out) *report_out = std::move(report);
  return image;
}

DecodedImage decode_file_with(const std::string& path, const DecodeOptions& options, DecodeReport* report,
                              SampleSink* sink) {
  const auto read_start = Clock::now();
  const std::vector<std::uint8_t> bytes = file_bytes(path, options.max_memory);
  const double read_ms = ms_since(read_start);
  DecodedImage image = decode_with(bytes, options, report, sink);
  if (report) report->times.read = read_ms;
  return image;
}

}  // namespace

void SampleSink::put_row_wide(std::size_t, std::size_t, std::size_t, std::span<const std::int64_t>) {
  throw DecodeError("this output takes samples of at most 31 bits");  // check_sink_takes refuses such images first
}

DecodedImage decode(std::span<const std::uint8_t> bytes, const DecodeOptions& options, DecodeReport* report) {
  return decode_with(bytes, options, report, nullptr);
}

DecodedImage decode_file(const std::string& path, const DecodeOptions& options, DecodeReport* report) {
  return decode_file_with(path, options, report, nullptr);
}

DecodedImage decode_to(std::span<const std::uint8_t> bytes, SampleSink& sink, const DecodeOptions& options,
                       DecodeReport* report) {
  return decode_with(bytes, options, report, &sink);
}

DecodedImage decode_file_to(const std::string& path, SampleSink& sink, const DecodeOptions& options,
                            DecodeReport* report) {
  return decode_file_with(path, options, report, &sink);
}

}  // namespace codec
