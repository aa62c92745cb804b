#include "tile_decoder.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <memory>
#include <optional>
#include <stdexcept>
#include <variant>

#include "block_decoder.h"
#include "byte_reader.h"
#include "codec/ht/ht_block_decoder.h"
#include "codec/structure/error.h"
#include "codec/tier2/progression.h"
#include "dwt/error.h"
#include "dwt/geometry.h"
#include "imageio/plane_memory.h"
#include "packet_reader.h"
#include "sample_output.h"

namespace codec::dec {

namespace {

using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point t0) { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); }

std::vector<ComponentSampling> sampling_of(const Siz& siz) {
  std::vector<ComponentSampling> s;
  for (const ComponentSize& c : siz.components) s.push_back(ComponentSampling{c.dx, c.dy});
  return s;
}

std::vector<CodingStyle> styles_of(const TileParams& p) {
  std::vector<CodingStyle> s;
  for (const TileComponentParams& c : p.components)
    s.push_back(CodingStyle{c.coding.levels, c.coding.xcb, c.coding.ycb, c.coding.precincts});
  return s;
}

// The step size entry of a band (A.6.4: LL, then HL, LH, HH of each level from the coarsest), or
// derived from LL's for scalar derived quantisation (E-5).
StepSize step_of(const Quantization& q, int levels, const Subband& band) {
  if (q.style == 1) {
    const StepSize ll = q.steps[0];
    return StepSize{ll.exponent - levels + band.level, ll.mantissa};
  }
  if (band.orientation == BandOrientation::LL) return q.steps[0];
  const std::size_t index = 1 + 3 * static_cast<std::size_t>(levels - band.level) +
                            static_cast<std::size_t>(static_cast<int>(band.orientation) - 1);
  return q.steps[index];
}

template <class T>
using PlaneSamples = std::vector<T, imageio::UninitialisedAllocator<T>>;

// A tile-component's samples between the stages: int32 for the reversible path, float for 9/7;
// `wide`, int64 and double instead, for components of more than 31 bits or code-blocks deeper than
// the int32 form holds (needs_wide_planes).
struct Plane {
  Rect rect;  // on the (reduced) component grid
  bool reversible = true;
  bool wide = false;
  // Uninitialised: tier-1 writes every sample, the blocks it does not decode as zeros, each
  // block's part on the thread that decodes it (decode_blocks). One of the four is used.
  PlaneSamples<std::int32_t> ints;
  PlaneSamples<float> floats;
  PlaneSamples<std::int64_t> wide_ints;
  PlaneSamples<double> doubles;
  int width() const { return static_cast<int>(rect.width()); }
  int height() const { return static_cast<int>(rect.height()); }
  // f(samples) with the vector in use (const for a const plane).
  template <class F>
  void visit(F&& f) {
    visit_samples(*this, f);
  }
  template <class F>
  void visit(F&& f) const {
    visit_samples(*this, f);
  }

 private:
  template <class Self, class F>
  static void visit_samples(Self& plane, F& f) {
    if (plane.wide)
      plane.reversible ? f(plane.wide_ints) : f(plane.doubles);
    else
      plane.reversible ? f(plane.ints) : f(plane.floats);
  }
};

// Whether a tile-component needs 64-bit planes: samples of more than 29 bits (the int32 5/3
// lifting adds two samples of up to 2^30 for 31-bit ones, and its coefficients outgrow 31 bits), or
// a band whose code-blocks may start above the int32 form's kMaxTopPlane: Mb = G + epsilon_b - 1
// (E-2) plus the ROI shift (H.1), the top plane Mb - 1 when no MSB is missing.
bool needs_wide_planes(const TileComponentParams& params, const ComponentSize& size) {
  if (size.precision > 29) return true;
  const Quantization& q = params.quantization;
  int largest_exponent = 0;  // derived quantisation (E-5) only lowers LL's exponent
  for (const StepSize& step : q.steps) largest_exponent = std::max(largest_exponent, step.exponent);
  return q.guard_bits + largest_exponent - 2 + params.roi_shift > kMaxTopPlane;
}

t2::ComponentGeometry geometry_of(const TileComponent& tc, int dx, int dy) {
  t2::ComponentGeometry g;
  g.dx = dx;
  g.dy = dy;
  for (const Resolution& r : tc.resolutions)
    g.resolutions.push_back(t2::ResolutionGeometry{r.rect.x0, r.rect.y0, r.rect.x1, r.rect.y1, r.ppx, r.ppy,
                                                   r.precincts_wide, r.precincts_high});
  return g;
}

bool is_ht(const ComponentCoding& coding) { return (coding.block_style & 0x40) != 0; }

// The HT set an HT code-block decodes (T.814 7.1.1, 8.3: one set, the last whose cleanup segment
// arrived, subsumes those before it): its cleanup segment, its plane (P missing MSBs place the first
// set's cleanup at Mb - 1 - P; each later set, the first ones being placeholders without bytes,
// codes one plane lower) and the refinement segment that follows it with its passes. Returns false
// when no cleanup pass arrived.
bool last_ht_set(const BlockState& st, int mb, codec::ht::HtCodewords& set) {
  const std::span<const std::uint8_t> data(st.data);
  std::size_t offset = 0;
  int pass = 0, chosen = -1;  // the chosen set's index
  for (const Segment& s : st.segments) {
    if (offset + s.bytes > data.size()) break;
    const auto bytes = data.subspan(offset, s.bytes);
    if (pass % 3 == 0 && s.bytes > 0) {
      chosen = pass / 3;
      set = codec::ht::HtCodewords{};
      set.cleanup = bytes;
      set.cleanup_plane = mb - 1 - st.missing_msbs - chosen;
    } else if (pass % 3 == 1 && pass / 3 == chosen) {
      set.refinement = bytes;
      set.refinement_passes = std::min(2, s.passes);
    }
    offset += s.bytes;
    pass += s.passes;
  }
  return chosen >= 0;
}

// Tier-1 (EBCOT or HT) of one code-block into `block` (w*h, every sample written), in the
// representation of decode_code_block, int32 or int64.
template <class Value>
void decode_block(const BlockState& st, int mb, int w, int h, BandOrientation orientation,
                  const ComponentCoding& coding, std::vector<Value>& block) {
  if (!is_ht(coding)) {
    BlockCodewords cw{st.data, st.segments, st.kept_passes, mb - 1 - st.missing_msbs};
    decode_code_block(cw, w, h, orientation, t1::BlockStyle::from_spcod(coding.block_style), std::span<Value>(block));
    return;
  }
  codec::ht::HtCodewords set;
  if (!last_ht_set(st, mb, set)) return std::fill(block.begin(), block.end(), 0);
  if (set.cleanup_plane < 0 || set.cleanup_plane > kMaxTopPlane)
    throw DecodeError("an HT code-block's cleanup pass is on bit-plane " + std::to_string(set.cleanup_plane) + " (Mb " +
                      std::to_string(mb) + ", " + std::to_string(st.missing_msbs) + " missing MSBs)");
  set.vertically_causal = t1::BlockStyle::from_spcod(coding.block_style).vertically_causal;
  // The HT block decoder works in int32 (its cleanup plane checked above): a block of a wide
  // plane is decoded there and widened.
  thread_local std::vector<std::int32_t> narrow;
  std::vector<std::int32_t>& out = [&]() -> std::vector<std::int32_t>& {
    if constexpr (std::is_same_v<Value, std::int32_t>)
      return block;
    else
      return narrow;
  }();
  out.resize(block.size());
  try {
    codec::ht::decode_ht_block(set, w, h, out);
  } catch (const codec::ht::HtDecodeError& e) {
    throw DecodeError(e.what());
  }
  if constexpr (!std::is_same_v<Value, std::int32_t>) std::copy(out.begin(), out.end(), block.begin());
}

// Whether a code-block of a band at decomposition level `level` can reach `window` (full-resolution
// tile-component coordinates) through the inverse DWT. A coefficient at band position u feeds,
// one level up, the samples within 4 of 2u (the 9/7's synthesis filters have 7 and 9 taps, the
// 5/3's fewer), and so, through the levels, samples within 4 * 2^level of u * 2^level: a margin of
// 4 band samples, plus one for the rounding of B-15, around the window scaled to the band.
bool reaches(const Rect& block, int level, const Rect& window) {
  constexpr std::int64_t kMargin = 5;
  const Rect scaled{floor_shift(window.x0, level) - kMargin, floor_shift(window.y0, level) - kMargin,
                    ceil_shift(window.x1, level) + kMargin, ceil_shift(window.y1, level) + kMargin};
  return !block.intersect(scaled).empty();
}

// One code-block's tier-1 and dequantisation, with what its band says about it.
struct BlockTask {
  const CodeBlock* block = nullptr;
  const BlockState* state = nullptr;
  BandOrientation orientation = BandOrientation::LL;
  int mb = 0;             // magnitude bit-planes
  int x = 0, y = 0;       // top-left in the plane's Mallat layout
  double half_delta = 0;  // irreversible: half the quantisation step
  std::int64_t roi_threshold = 0;
  bool decoded = true;  // false: no pass arrived, or the block cannot reach the window: zeros
};

// H.2: coefficients at or above 2^s (`threshold`, in the decoder's doubled representation) belong to
// the region and were scaled up by s.
template <class Value>
void descale_roi(std::span<Value> block, std::int64_t threshold, int roi_shift) {
  for (Value& v : block) {
    const Value m = v < 0 ? -v : v;
    if (m >= threshold) v = v < 0 ? -(m >> roi_shift) : (m >> roi_shift);
  }
}

// A decoded w x h block's coefficients into its place in the plane, dequantised: the exact integer
// (the half-step dropped) or the value times the quantisation step (E.1.1.2). No zeros: zero
// coefficients are written as such, and left-out blocks by clear_block.
// An int32 block goes to an int32 or float plane, an int64 block to an int64 or double one.
template <class Value>
void dequantise_block(std::span<const Value> block, int w, int h, const BlockTask& t, Plane& plane) {
  const auto stride = static_cast<std::size_t>(plane.width()), width = static_cast<std::size_t>(w);
  plane.visit([&](auto& samples) {
    using Sample = typename std::remove_reference_t<decltype(samples)>::value_type;
    if constexpr (sizeof(Sample) == sizeof(Value)) {
      const auto half_delta = static_cast<Sample>(t.half_delta);
      for (int y = 0; y < h; ++y) {
        const Value* in = block.data() + static_cast<std::size_t>(y) * width;
        Sample* out = samples.data() + static_cast<std::size_t>(t.y + y) * stride + static_cast<std::size_t>(t.x);
        if constexpr (std::is_integral_v<Sample>)
          for (std::size_t x = 0; x < width; ++x) out[x] = in[x] / 2;
        else
          for (std::size_t x = 0; x < width; ++x) out[x] = static_cast<Sample>(in[x]) * half_delta;
      }
    }
  });
}

// Faults in the pages of a new plane before its code-blocks are decoded into it, each thread
// taking whole 2 MiB runs (one page-table page each). The blocks would otherwise first touch the
// pages in their own order: a 64x64 block of a 4096-wide float plane writes 256 bytes into each of
// 64 pages, and the blocks side by side on 16 threads all fault into the same pages and the same
// page-table pages at once, contending for the same locks. That serialised the 4096x4096 0.75 bpp
// decode on 16 threads (most of its blocks are empty, so faulting is most of their work).
void fault_in(void* data, std::size_t bytes, base::ThreadPool& pool) {
  constexpr std::size_t kRun = imageio::kHugePageBytes, kPage = 4096;
  if (pool.size() < 2 || bytes < 2 * kRun) return;
  auto* const first = static_cast<unsigned char*>(data);
  pool.parallel_for((bytes + kRun - 1) / kRun, [&](std::size_t k) {
    volatile unsigned char* const run = first + k * kRun;  // volatile: the stores are the point
    const std::size_t end = std::min(kRun, bytes - k * kRun);
    // One call for the run's pages where the kernel has it, instead of a fault per page: 7 % less
    // CPU time for a 0.75 bpp 2048x2048 decode on 2 threads (2026-11-28).
    if (imageio::populate_for_writing(first + k * kRun, end)) return;
    for (std::size_t at = 0; at < end; at += kPage) run[at] = 0;
  });
}

// The w x h zeros of a block tier-1 leaves out.
void clear_block(int w, int h, const BlockTask& t, Plane& plane) {
  const auto stride = static_cast<std::size_t>(plane.width()), width = static_cast<std::size_t>(w);
  plane.visit([&](auto& samples) {
    for (int y = 0; y < h; ++y)
      std::fill_n(samples.data() + static_cast<std::size_t>(t.y + y) * stride + static_cast<std::size_t>(t.x), width,
                  0);
  });
}

// Tier-1 of one code-block in `Value`s (one buffer per worker, reused), ROI de-scaling and
// dequantisation into its place in the plane.
template <class Value>
void decode_into_plane(const BlockTask& t, const ComponentCoding& coding, int roi_shift, Plane& plane) {
  const int w = static_cast<int>(t.block->rect.width()), h = static_cast<int>(t.block->rect.height());
  thread_local std::vector<Value> block;
  block.resize(static_cast<std::size_t>(w) * static_cast<std::size_t>(h));  // tier-1 writes every sample
  decode_block(*t.state, t.mb, w, h, t.orientation, coding, block);
  if (t.roi_threshold) descale_roi(std::span<Value>(block), t.roi_threshold, roi_shift);
  dequantise_block(std::span<const Value>(block), w, h, t, plane);
}

// Tier-1 and dequantisation of every code-block of a tile-component that reaches `window`, into
// its plane in the Mallat layout of the (reduced) inverse DWT, timed into `times`. The
// blocks write disjoint parts of the plane, so they are decoded side by side on `pool`.
void decode_blocks(const TileComponent& tc, const TileComponentParams& params, const ComponentSize& size, int reduce,
                   const Rect& window, const std::vector<BlockState>& states, Plane& plane, base::ThreadPool& pool,
                   DecodeStageTimes& times) {
  const int kept_levels = tc.levels - reduce;
  const auto geometry =
      dwt::decomposition(plane.width(), plane.height(), dwt::Origin{plane.rect.x0, plane.rect.y0}, kept_levels);
  std::vector<BlockTask> tasks;
  std::size_t covered = 0;  // samples of the plane the blocks cover
  for (int r = 0; r <= kept_levels; ++r) {
    const Resolution& res = tc.resolutions[static_cast<std::size_t>(r)];
    for (std::size_t bi = 0; bi < res.bands.size(); ++bi) {
      const Subband& band = res.bands[bi];
      if (band.rect.empty()) continue;
      const dwt::LayoutRect layout =
          r == 0 ? dwt::LayoutRect{0, 0, static_cast<int>(band.rect.width()), static_cast<int>(band.rect.height())}
                 : dwt::band_rect(geometry, band.level - reduce, band.orientation);
      const StepSize step = step_of(params.quantization, tc.levels, band);
      BlockTask task;
      task.orientation = band.orientation;
      // E-2: Mb = G + epsilon_b - 1 magnitude bit-planes, plus the ROI shift (H.1).
      task.mb = params.quantization.guard_bits + step.exponent - 1 + params.roi_shift;
      const double delta =
          std::ldexp(1.0 + step.mantissa / 2048.0, size.precision + band_gain(band.orientation) - step.exponent);
      // Rounded to float once, as the narrow plane multiplies in float.
      task.half_delta = plane.wide ? delta / 2 : static_cast<double>(static_cast<float>(delta / 2));
      const int most_shift = plane.wide ? kMaxWideTopPlane : kMaxTopPlane;
      task.roi_threshold =
          params.roi_shift > 0 && params.roi_shift <= most_shift ? (std::int64_t{2} << params.roi_shift) : 0;
      for (const Precinct& p : res.precincts)
        for (const PrecinctBand& pb : p.bands) {
          if (pb.band != static_cast<int>(bi)) continue;
          for (const CodeBlock& cb : pb.blocks) {
            const BlockState& st = states[cb.index];
            task.decoded = st.kept_passes > 0 && reaches(cb.rect, band.level, window);
            covered += static_cast<std::size_t>(cb.rect.width()) * static_cast<std::size_t>(cb.rect.height());
            task.block = &cb;
            task.state = &st;
            task.x = layout.x + static_cast<int>(cb.rect.x0 - band.rect.x0);
            task.y = layout.y + static_cast<int>(cb.rect.y0 - band.rect.y0);
            tasks.push_back(task);
          }
        }
    }
  }
  const auto tier1_start = Clock::now();
  // The code-blocks of the kept resolutions tile the plane (B.5, B.7), so that each sample is
  // written by one task; should a geometry ever leave a gap, the plane is cleared first.
  if (covered != static_cast<std::size_t>(plane.width()) * static_cast<std::size_t>(plane.height()))
    plane.visit([](auto& samples) { std::fill(samples.begin(), samples.end(), 0); });
  const int roi_shift = params.roi_shift;
  pool.parallel_for(tasks.size(), [&](std::size_t k) {
    const BlockTask& t = tasks[k];
    const int w = static_cast<int>(t.block->rect.width()), h = static_cast<int>(t.block->rect.height());
    if (!t.decoded) return clear_block(w, h, t, plane);
    if (plane.wide)
      decode_into_plane<std::int64_t>(t, params.coding, roi_shift, plane);
    else
      decode_into_plane<std::int32_t>(t, params.coding, roi_shift, plane);
  });
  times.tier1 += ms_since(tier1_start);
}

// The inverse DWT of one plane; a device backend's time is split into its stages as the encoder
// splits the forward one (anything around the device's own stages counts as upload).
void inverse_dwt(Plane& plane, int levels, const TileDecodeSetup& setup) {
  if (levels <= 0 || plane.rect.empty()) return;
  DecodeStageTimes& times = *setup.times;
  const auto start = Clock::now();
  dwt::DwtParams p;
  p.kernel = plane.reversible ? dwt::KernelId::Reversible53 : dwt::KernelId::Irreversible97;
  p.levels = levels;
  p.origin = dwt::Origin{plane.rect.x0, plane.rect.y0};
  p.levels_may_exceed_size = true;
  if (plane.wide) {  // on the CPU alone
    if (plane.reversible)
      setup.wide_backend->inverse(dwt::make_span(plane.wide_ints.data(), plane.width(), plane.height()), p);
    else
      setup.wide_backend->inverse(dwt::make_span(plane.doubles.data(), plane.width(), plane.height()), p);
    times.dwt += ms_since(start);
    return;
  }
  dwt::DwtBackend& backend = plane.reversible ? *setup.reversible_backend : *setup.irreversible_backend;
  if (plane.reversible)
    backend.inverse(dwt::make_span(plane.ints.data(), plane.width(), plane.height()), p);
  else
    backend.inverse(dwt::make_span(plane.floats.data(), plane.width(), plane.height()), p);
  const double whole = ms_since(start);
  if (const dwt::DeviceTimings* device = backend.device_timings()) {
    const dwt::DeviceTimings& g = *device;
    times.dwt += g.compute_ms;
    times.download += g.download_ms;
    times.upload += whole - g.compute_ms - g.download_ms - g.context_ms - g.compile_ms;
    times.gl_context += g.context_ms;
    times.shader_compile += g.compile_ms;
  } else {
    times.dwt += whole;
  }
}

// Rows [y0, y1) through fn(y), in bands of rows spread over the pool.
template <class RowFunction>
void for_rows(std::int64_t y0, std::int64_t y1, base::ThreadPool& pool, const RowFunction& fn) {
  constexpr std::int64_t kRowsPerTask = 16;  // a few tens of KiB per task: little overhead per row
  const auto tasks = static_cast<std::size_t>((y1 - y0 + kRowsPerTask - 1) / kRowsPerTask);
  pool.parallel_for(tasks, [&](std::size_t k) {
    const std::int64_t first = y0 + static_cast<std::int64_t>(k) * kRowsPerTask;
    for (std::int64_t y = first; y < std::min(y1, first + kRowsPerTask); ++y) fn(y);
  });
}

// Sample (x, y) of a plane or an output component (their own grid's coordinates).
template <class T, class Allocator>
const T* plane_at(const std::vector<T, Allocator>& samples, const Plane& plane, std::int64_t x, std::int64_t y) {
  return samples.data() + static_cast<std::size_t>(y - plane.rect.y0) * static_cast<std::size_t>(plane.width()) +
         static_cast<std::size_t>(x - plane.rect.x0);
}
Rect output_rect(const DecodedComponent& out) {
  return Rect{out.x0, out.y0, std::int64_t{out.x0} + out.width, std::int64_t{out.y0} + out.height};
}

// Where a tile's finished rows go: straight into the output components' samples, or through a
// row of scratch (one per thread and component, reused) to the caller's sink.
class RowOutput {
 public:
  RowOutput(DecodedImage& image, SampleSink* sink) : image_(image), sink_(sink) {}

  // Where output component c's samples [x, x + n) of row y (its grid's coordinates) are to be made.
  std::int32_t* row(std::size_t c, std::int64_t x, std::int64_t y, std::size_t n) const {
    if (sink_) {
      thread_local std::array<std::vector<std::int32_t>, 3> scratch;
      std::vector<std::int32_t>& s = scratch[std::min<std::size_t>(c, 2)];
      if (s.size() < n) s.resize(n);
      return s.data();
    }
    return sample_at(image_.components[c].samples, c, x, y);
  }
  // The row made where row() said is finished.
  void done(std::size_t c, std::int64_t x, std::int64_t y, const std::int32_t* samples, std::size_t n) const {
    if (!sink_) return;
    const DecodedComponent& out = image_.components[c];
    sink_->put_row(c, static_cast<std::size_t>(x - out.x0), static_cast<std::size_t>(y - out.y0), {samples, n});
  }
  // The same for an output component of more than 31 bits (DecodedComponent::wide_samples).
  std::int64_t* wide_row(std::size_t c, std::int64_t x, std::int64_t y, std::size_t n) const {
    if (sink_) {
      thread_local std::vector<std::int64_t> scratch;
      if (scratch.size() < n) scratch.resize(n);
      return scratch.data();
    }
    return sample_at(image_.components[c].wide_samples, c, x, y);
  }
  void done_wide(std::size_t c, std::int64_t x, std::int64_t y, const std::int64_t* samples, std::size_t n) const {
    if (!sink_) return;
    const DecodedComponent& out = image_.components[c];
    sink_->put_row_wide(c, static_cast<std::size_t>(x - out.x0), static_cast<std::size_t>(y - out.y0), {samples, n});
  }
  // Row y's samples [x, x + n) of output component c, made in int64, stored as the component keeps them.
  void put(std::size_t c, std::int64_t x, std::int64_t y, const std::int64_t* values, std::size_t n) const {
    if (image_.components[c].precision > 31) {
      std::int64_t* row = wide_row(c, x, y, n);
      std::copy_n(values, n, row);
      return done_wide(c, x, y, row, n);
    }
    std::int32_t* row = this->row(c, x, y, n);
    for (std::size_t i = 0; i < n; ++i) row[i] = static_cast<std::int32_t>(values[i]);  // clamped to 31 bits
    done(c, x, y, row, n);
  }
  // Components 0..2's rows, all made and all output, with the same geometry.
  void done012(std::int64_t x, std::int64_t y, const OutputRows& rows, std::size_t n) const {
    if (!sink_) return;
    const DecodedComponent& out = image_.components[0];
    sink_->put_rows012(static_cast<std::size_t>(x - out.x0), static_cast<std::size_t>(y - out.y0), {rows[0], n},
                       {rows[1], n}, {rows[2], n});
  }

 private:
  // Sample (x, y) of output component c (its grid's coordinates) in `samples`, its int32 or int64 ones.
  template <class T>
  T* sample_at(std::vector<T>& samples, std::size_t c, std::int64_t x, std::int64_t y) const {
    const DecodedComponent& out = image_.components[c];
    return samples.data() + static_cast<std::size_t>(y - out.y0) * static_cast<std::size_t>(out.width) +
           static_cast<std::size_t>(x - out.x0);
  }

  DecodedImage& image_;
  SampleSink* sink_;
};

// G.1.2 on one plane without a component transform: level shift, rounding (9/7) and clamping into
// the part of output component c the plane covers.
void store(const Plane& plane, const ComponentSize& size, std::size_t c, const RowOutput& output,
           const DecodedComponent& out, base::ThreadPool& pool) {
  const SampleRange range = sample_range(size.precision, size.is_signed);
  const Rect area = plane.rect.intersect(output_rect(out));
  if (area.empty()) return;
  const auto n = static_cast<std::size_t>(area.width());
  for_rows(area.y0, area.y1, pool, [&](std::int64_t y) {
    std::int32_t* row = output.row(c, area.x0, y, n);
    if (plane.reversible)
      ints_to_samples(plane_at(plane.ints, plane, area.x0, y), range, row, n);
    else
      floats_to_samples(plane_at(plane.floats, plane, area.x0, y), range, row, n);
    output.done(c, area.x0, y, row, n);
  });
}

// G.2 and G.1.2 on components 0..2 in one pass: the inverse RCT or ICT of the three planes, then
// each output component's level shift, rounding and clamping. `outputs` holds the selected ones
// (null: decoded for the transform only), all covering the same part of the planes.
void store_transformed(const std::array<const Plane*, 3>& planes, const std::array<const DecodedComponent*, 3>& outputs,
                       const RowOutput& output, const OutputRanges& ranges, const Rect& area, base::ThreadPool& pool) {
  const Plane &p0 = *planes[0], &p1 = *planes[1], &p2 = *planes[2];
  const auto n = static_cast<std::size_t>(area.width());
  const bool all_three = outputs[0] && outputs[1] && outputs[2];
  for_rows(area.y0, area.y1, pool, [&](std::int64_t y) {
    OutputRows rows{};
    for (std::size_t c = 0; c < 3; ++c) rows[c] = outputs[c] ? output.row(c, area.x0, y, n) : nullptr;
    if (p0.reversible)
      rct_to_samples(plane_at(p0.ints, p0, area.x0, y), plane_at(p1.ints, p1, area.x0, y),
                     plane_at(p2.ints, p2, area.x0, y), ranges, rows, n);
    else
      ict_to_samples(plane_at(p0.floats, p0, area.x0, y), plane_at(p1.floats, p1, area.x0, y),
                     plane_at(p2.floats, p2, area.x0, y), ranges, rows, n);
    if (all_three) {
      output.done012(area.x0, y, rows, n);
    } else {
      for (std::size_t c = 0; c < 3; ++c)
        if (rows[c]) output.done(c, area.x0, y, rows[c], n);
    }
  });
}

// G.2's condition on components 0..2.
void check_transformable(const std::vector<Plane>& planes) {
  const Plane &p0 = planes[0], &p1 = planes[1], &p2 = planes[2];
  if (p0.rect != p1.rect || p0.rect != p2.rect)
    throw DecodeError("the component transform needs equal tile-components");
  if (p0.reversible != p1.reversible || p0.reversible != p2.reversible)
    throw DecodeError("the component transform needs components 0..2 all reversible or all irreversible");
}

// n samples of a plane's row y from x, whatever the plane holds, as T: int64 for a reversible
// plane, double for an irreversible one.
template <class T>
void load_row(const Plane& plane, std::int64_t x, std::int64_t y, std::size_t n, T* out) {
  plane.visit([&](const auto& samples) {
    const auto* in = plane_at(samples, plane, x, y);
    for (std::size_t i = 0; i < n; ++i) out[i] = static_cast<T>(in[i]);
  });
}

// store_tile for tiles with 64-bit planes or outputs of more than 31 bits: the same steps, one
// sample at a time in int64 and double, and each transformed component in a pass of its own
// (such images are rare; their exactness matters more than their speed).
void store_tile_wide(const std::vector<Plane>& planes, bool mct, const Siz& siz, const std::vector<bool>& selected,
                     DecodedImage& image, SampleSink* sink, base::ThreadPool& pool) {
  const RowOutput output(image, sink);
  // Row y of output component c over [area.x0, area.x1), from make(values, x, y, n).
  auto store_rows = [&](std::size_t c, const Rect& area, const auto& make) {
    if (area.empty()) return;
    const auto n = static_cast<std::size_t>(area.width());
    for_rows(area.y0, area.y1, pool, [&](std::int64_t y) {
      thread_local std::vector<std::int64_t> values;
      values.resize(n);
      make(values.data(), area.x0, y, n);
      output.put(c, area.x0, y, values.data(), n);
    });
  };
  std::size_t first_plain = 0;
  if (mct) {
    check_transformable(planes);
    for (std::size_t c = 0; c < 3; ++c) {
      if (!selected[c]) continue;
      const WideSampleRange range = wide_sample_range(siz.components[c].precision, siz.components[c].is_signed);
      const auto transformed = [&](std::int64_t* values, std::int64_t x, std::int64_t y, std::size_t n) {
        auto components = [&]<class T>(std::array<std::vector<T>, 3>& rows) {
          for (std::size_t k = 0; k < 3; ++k) {
            rows[k].resize(n);
            load_row(planes[k], x, y, n, rows[k].data());
          }
        };
        if (planes[0].reversible) {
          thread_local std::array<std::vector<std::int64_t>, 3> rows;
          components(rows);
          for (std::size_t i = 0; i < n; ++i)
            values[i] = wide_sample(inverse_rct(rows[0][i], rows[1][i], rows[2][i], c), range);
        } else {
          thread_local std::array<std::vector<double>, 3> rows;
          components(rows);
          for (std::size_t i = 0; i < n; ++i)
            values[i] = wide_sample(inverse_ict(rows[0][i], rows[1][i], rows[2][i], c), range);
        }
      };
      store_rows(c, planes[0].rect.intersect(output_rect(image.components[c])), transformed);
    }
    first_plain = 3;
  }
  for (std::size_t c = first_plain; c < planes.size(); ++c) {
    if (!selected[c]) continue;
    const Plane& plane = planes[c];
    const WideSampleRange range = wide_sample_range(siz.components[c].precision, siz.components[c].is_signed);
    store_rows(c, plane.rect.intersect(output_rect(image.components[c])),
               [&](std::int64_t* values, std::int64_t x, std::int64_t y, std::size_t n) {
                 if (plane.reversible) {
                   load_row(plane, x, y, n, values);
                   for (std::size_t i = 0; i < n; ++i) values[i] = wide_sample(values[i], range);
                 } else {
                   thread_local std::vector<double> row;
                   row.resize(n);
                   load_row(plane, x, y, n, row.data());
                   for (std::size_t i = 0; i < n; ++i) values[i] = wide_sample(row[i], range);
                 }
               });
  }
}

// The tile's planes into the output image: components 0..2 through the inverse component
// transform when `mct`, every selected component level-shifted and clamped; the rows on the pool.
void store_tile(const std::vector<Plane>& planes, bool mct, const Siz& siz, const std::vector<bool>& selected,
                DecodedImage& image, SampleSink* sink, base::ThreadPool& pool) {
  if (std::any_of(planes.begin(), planes.end(), [](const Plane& p) { return p.wide; }))
    return store_tile_wide(planes, mct, siz, selected, image, sink, pool);
  const RowOutput output(image, sink);
  std::size_t first_plain = 0;  // components from here on have no component transform
  if (mct) {
    check_transformable(planes);
    const Plane &p0 = planes[0], &p1 = planes[1], &p2 = planes[2];
    std::array<const DecodedComponent*, 3> outputs{};
    OutputRanges ranges{};
    for (std::size_t c = 0; c < 3; ++c) {
      ranges[c] = sample_range(siz.components[c].precision, siz.components[c].is_signed);
      if (selected[c]) outputs[c] = &image.components[c];
    }
    // Components with other sampling factors may cover other parts of the planes: then one pass each.
    std::optional<Rect> shared;
    bool same_area = true;
    for (std::size_t c = 0; c < 3; ++c) {
      if (!outputs[c]) continue;
      const Rect own = p0.rect.intersect(output_rect(*outputs[c]));
      if (!shared) shared = own;
      same_area = same_area && own == *shared;
    }
    const std::array<const Plane*, 3> transformed{&p0, &p1, &p2};
    if (same_area) {
      if (shared && !shared->empty()) store_transformed(transformed, outputs, output, ranges, *shared, pool);
    } else {
      for (std::size_t c = 0; c < 3; ++c) {
        if (!outputs[c]) continue;
        std::array<const DecodedComponent*, 3> one{};
        one[c] = outputs[c];
        const Rect own = p0.rect.intersect(output_rect(*outputs[c]));
        if (!own.empty()) store_transformed(transformed, one, output, ranges, own, pool);
      }
    }
    first_plain = 3;
  }
  for (std::size_t c = first_plain; c < planes.size(); ++c)
    if (selected[c]) store(planes[c], siz.components[c], c, output, image.components[c], pool);
}

// The tile's packets in the order they were sent: COD's progression, or with POC (A.6.6, B.12.2)
// each progression in turn over its layer, resolution and component ranges, skipping packets an
// earlier progression already sent. A packet no progression reaches is not in the stream.
std::vector<t2::PacketId> packet_order(const TileParams& params, const Tile& tile,
                                       const std::vector<t2::ComponentGeometry>& geometry) {
  auto full_order = [&](t2::Order order) {
    return t2::progression(order, params.cod.layers, tile.rect.x0, tile.rect.y0, tile.rect.x1, tile.rect.y1, geometry);
  };
  if (params.poc.empty()) return full_order(params.cod.order);

  // Packet (l, r, c, k) is bit index ((first[c] + precincts before r) + k) * layers + l.
  std::vector<std::vector<std::size_t>> first(geometry.size());
  std::size_t total = 0;
  for (std::size_t c = 0; c < geometry.size(); ++c)
    for (const t2::ResolutionGeometry& r : geometry[c].resolutions) {
      first[c].push_back(total);
      total += static_cast<std::size_t>(r.precincts_wide) * static_cast<std::size_t>(r.precincts_high);
    }
  const auto layers = static_cast<std::size_t>(params.cod.layers);
  // Each progression filters a whole progression of the tile: refuse what would take too long.
  if (static_cast<double>(params.poc.size()) * static_cast<double>(total) * static_cast<double>(layers) > 5e8)
    throw DecodeError("tile " + std::to_string(tile.index) + ": " + std::to_string(params.poc.size()) +
                      " progression changes over " + std::to_string(total * layers) +
                      " packets is more than the decoder walks");
  std::vector<bool> sent(total * layers, false);
  std::vector<std::vector<t2::PacketId>> by_order(5);
  std::vector<t2::PacketId> out;
  for (const ProgressionChange& change : params.poc) {
    auto& order = by_order[static_cast<std::size_t>(change.order)];
    if (order.empty()) order = full_order(change.order);
    for (const t2::PacketId& id : order) {
      if (id.layer >= change.layer_end || id.resolution < change.res_start || id.resolution >= change.res_end ||
          id.component < change.comp_start || id.component >= change.comp_end)
        continue;
      const std::size_t bit = (first[static_cast<std::size_t>(id.component)][static_cast<std::size_t>(id.resolution)] +
                               static_cast<std::size_t>(id.precinct)) *
                                  layers +
                              static_cast<std::size_t>(id.layer);
      if (sent[bit]) continue;
      sent[bit] = true;
      out.push_back(id);
    }
  }
  return out;
}

std::vector<std::uint8_t> joined(const TileStream& tile) {
  std::vector<std::uint8_t> out;
  for (const auto& part : tile.parts) out.insert(out.end(), part.begin(), part.end());
  return out;
}

}  // namespace

double tile_working_set(const Codestream& cs, const TileParams& params, int tile_index, int reduce) {
  const Rect tile = cs.siz.grid.tile_rect(tile_index);
  double bytes = 0;
  for (std::size_t c = 0; c < params.components.size(); ++c) {
    const ComponentSize& size = cs.siz.components[c];
    const ComponentCoding& coding = params.components[c].coding;
    const Rect tc = tile_component_rect(tile, size.dx, size.dy);
    if (tc.width() >= (std::int64_t{1} << 31) || tc.height() >= (std::int64_t{1} << 31))
      throw DecodeError("tile " + std::to_string(tile_index) + " is too large (a side of 2^31 samples or more)");
    const double sample_bytes = needs_wide_planes(params.components[c], size) ? 8.0 : 4.0;
    bytes += static_cast<double>(tc.width()) * static_cast<double>(tc.height()) * sample_bytes / std::pow(4.0, reduce);
    const CodingStyle style{coding.levels, coding.xcb, coding.ycb, coding.precincts};
    for (int r = 0; r <= coding.levels; ++r) {
      const int shift = coding.levels - r;
      const Rect res{ceil_shift(tc.x0, shift), ceil_shift(tc.y0, shift), ceil_shift(tc.x1, shift),
                     ceil_shift(tc.y1, shift)};
      if (res.empty()) continue;
      const auto [ppx, ppy] = style.precinct(r);
      const double pw = static_cast<double>(ceil_shift(res.x1, ppx) - floor_shift(res.x0, ppx));
      const double ph = static_cast<double>(ceil_shift(res.y1, ppy) - floor_shift(res.y0, ppy));
      const int bands = r == 0 ? 1 : 3;
      const int bx = std::min(coding.xcb, r == 0 ? ppx : ppx - 1), by = std::min(coding.ycb, r == 0 ? ppy : ppy - 1);
      // Code-blocks of a band: its cells plus one per precinct edge that cuts a cell.
      const double cells =
          (std::ceil(static_cast<double>(res.width()) / 2 / std::ldexp(1.0, std::max(bx, 0))) + pw + 1) *
          (std::ceil(static_cast<double>(res.height()) / 2 / std::ldexp(1.0, std::max(by, 0))) + ph + 1);
      const double blocks = r == 0 ? cells * 2 : cells * bands;
      bytes += pw * ph * (sizeof(Precinct) + bands * (sizeof(PrecinctBand) + 2 * sizeof(TagTreeDecoder) + 64));
      bytes += pw * ph * static_cast<double>(params.cod.layers) * sizeof(t2::PacketId);
      bytes += blocks * (sizeof(CodeBlock) + sizeof(BlockState) + 2 * 16);
    }
  }
  return bytes;
}

void decode_tile(const Codestream& cs, const TileStream& tile_stream, const TileDecodeSetup& setup,
                 DecodedImage& image) {
  const DecodeOptions& options = *setup.options;
  DecodeStageTimes& times = *setup.times;
  const auto tier2_start = Clock::now();
  const TileParams params = resolve_tile_params(cs, tile_stream);
  const int reduce = options.reduce;
  for (std::size_t c = 0; c < params.components.size(); ++c)
    if (params.components[c].coding.levels < reduce)
      throw DecodeError("--reduce " + std::to_string(reduce) + " exceeds the " +
                        std::to_string(params.components[c].coding.levels) + " decomposition levels of component " +
                        std::to_string(c) + " in tile " + std::to_string(tile_stream.index));
  const double need = tile_working_set(cs, params, tile_stream.index, reduce);
  if (need > static_cast<double>(setup.memory_budget))
    throw DecodeError("tile " + std::to_string(tile_stream.index) + " would need about " +
                      std::to_string(static_cast<long long>(need / 1048576)) + " MiB, over the memory limit");

  Tile tile;
  try {
    tile = build_tile(cs.siz.grid, sampling_of(cs.siz), styles_of(params), tile_stream.index);
  } catch (const EncodeError& e) {
    throw DecodeError("tile " + std::to_string(tile_stream.index) + ": " + e.what());
  }

  // Tier-2: every packet in progression order.
  std::vector<t2::ComponentGeometry> geometry;
  for (std::size_t c = 0; c < tile.components.size(); ++c)
    geometry.push_back(geometry_of(tile.components[c], cs.siz.components[c].dx, cs.siz.components[c].dy));
  std::vector<t2::PacketId> packets;
  try {
    packets = packet_order(params, tile, geometry);
  } catch (const std::invalid_argument& e) {
    throw DecodeError("tile " + std::to_string(tile_stream.index) + ": " + e.what());
  }
  // Components decoded: those output, and those the component transform needs to make them.
  std::vector<bool> needed = setup.selected;
  if (params.cod.mct == 1 && (needed[0] || needed[1] || needed[2])) needed[0] = needed[1] = needed[2] = true;
  std::vector<BlockState> blocks(tile.code_blocks);
  std::vector<std::vector<std::vector<std::vector<PrecinctBandTrees>>>> trees(tile.components.size());
  for (std::size_t c = 0; c < tile.components.size(); ++c)
    for (const Resolution& r : tile.components[c].resolutions) trees[c].emplace_back(r.precincts.size());

  std::vector<std::uint8_t> joined_parts;
  std::span<const std::uint8_t> data;
  if (tile_stream.parts.size() == 1) {
    data = tile_stream.parts[0];
  } else {
    joined_parts = joined(tile_stream);
    data = joined_parts;
  }
  std::size_t pos = 0;
  PackedHeaders packed{tile_stream.headers, 0};
  for (const t2::PacketId& id : packets) {
    const auto c = static_cast<std::size_t>(id.component), r = static_cast<std::size_t>(id.resolution),
               k = static_cast<std::size_t>(id.precinct);
    const TileComponent& tc = tile.components[c];
    PacketContext ctx;
    ctx.sop = params.cod.sop;
    ctx.eph = params.cod.eph;
    ctx.packed = tile_stream.packed_headers ? &packed : nullptr;
    ctx.style = t1::BlockStyle::from_spcod(params.components[c].coding.block_style);
    ctx.ht = is_ht(params.components[c].coding);
    ctx.keep =
        (options.max_layers <= 0 || id.layer < options.max_layers) && id.resolution <= tc.levels - reduce && needed[c];
    try {
      pos = read_packet(data, pos, tile_stream.first_offset, tc.resolutions[r].precincts[k], id.layer, trees[c][r][k],
                        blocks, ctx);
    } catch (const PacketTruncated& e) {
      image.warnings.push_back("truncated: tile " + std::to_string(tile_stream.index) + ": " + e.what() +
                               "; the tile is decoded from the packets before it");
      break;
    }
  }
  trees.clear();
  times.tier2 += ms_since(tier2_start);

  // Tier-1, dequantisation and the inverse DWT per tile-component, then the component transform.
  std::vector<Plane> planes(tile.components.size());
  for (std::size_t c = 0; c < tile.components.size(); ++c) {
    if (!needed[c]) continue;
    const TileComponent& tc = tile.components[c];
    const ComponentSize& size = cs.siz.components[c];
    Plane& plane = planes[c];
    plane.rect = tc.resolutions[static_cast<std::size_t>(tc.levels - reduce)].rect;
    plane.reversible = params.components[c].coding.reversible;
    const std::size_t n = static_cast<std::size_t>(plane.rect.width()) * static_cast<std::size_t>(plane.rect.height());
    const auto clear_start = Clock::now();  // allocating the plane is tier-1's
    plane.wide = needs_wide_planes(params.components[c], size);
    plane.visit([&](auto& samples) {
      imageio::resize_with_huge_pages(samples, n);
      fault_in(samples.data(), n * sizeof(samples[0]), *setup.pool);
    });
    times.tier1 += ms_since(clear_start);
    decode_blocks(tc, params.components[c], size, reduce, tile_component_rect(setup.window, size.dx, size.dy), blocks,
                  plane, *setup.pool, times);
    try {
      inverse_dwt(plane, tc.levels - reduce, setup);
    } catch (const dwt::DwtError& e) {
      throw DecodeError("tile " + std::to_string(tile_stream.index) + ": inverse DWT: " + e.what());
    }
  }
  const auto transform_start = Clock::now();
  blocks.clear();
  store_tile(planes, params.cod.mct == 1 && needed[0], cs.siz, setup.selected, image, setup.sink, *setup.pool);
  times.component_transform += ms_since(transform_start);
}

}  // namespace codec::dec
