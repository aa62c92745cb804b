#include "codec/t1/block_encoder.h"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "coding_passes.h"
#include "coefficient_state.h"
#include "contexts.h"
#include "pass_schedule.h"
#include "raw_writer.h"

namespace codec::t1 {

namespace {

// A block stops after two bit-planes in a row that bought less than the stop rule's slope; or
// after one, once the block has had a plane above it and the plane below does not swell (see
// stops_after_quiet_plane).
constexpr int kQuietPlanesToStop = 2;
// The fewest bytes a pass that buys distortion takes, for the stop rule's bound on a block's best
// slope. (A first pass can in principle need no byte, when the decoder's 1-fill happens to spell its
// symbols; rate control's check catches a block skipped on that account.)
constexpr double kLeastPassBytes = 1;

void validate_dimensions(int width, int height, int magnitude_bitplanes) {
  if (width < 1 || height < 1)
    throw std::invalid_argument("code-block must be at least 1x1, got " + std::to_string(width) + "x" +
                                std::to_string(height));
  if (magnitude_bitplanes < 0 || magnitude_bitplanes > 31)
    throw std::invalid_argument("magnitude bit-planes must be 0..31, got " + std::to_string(magnitude_bitplanes));
}

// A block in its plane.
void validate_shape(const void* origin, std::ptrdiff_t stride, int width, int height, int magnitude_bitplanes) {
  validate_dimensions(width, height, magnitude_bitplanes);
  if (origin == nullptr || stride < width)
    throw std::invalid_argument("code-block rows " + std::to_string(stride) + " apart are narrower than its width " +
                                std::to_string(width));
}

// A block given as its own array.
void validate(std::span<const std::int32_t> coefficients, int width, int height, int magnitude_bitplanes) {
  validate_dimensions(width, height, magnitude_bitplanes);
  if (coefficients.size() != static_cast<std::size_t>(width) * static_cast<std::size_t>(height))
    throw std::invalid_argument("code-block of " + std::to_string(width) + "x" + std::to_string(height) + " given " +
                                std::to_string(coefficients.size()) + " coefficients");
}

void validate(const StopRule& stop, Distortion distortion) {
  if (distortion == Distortion::Skipped && stop.min_slope > 0)
    throw std::invalid_argument("a stop rule needs the passes' distortion measured");
}

// A pass whose codeword length is only known once its segment has been terminated.
struct PendingPass {
  int pass;
  bool raw;
  MqTruncationPoint point;       // MQ passes
  RawTruncationPoint raw_point;  // raw passes
};

// Segment bookkeeping: which coder is open, and the passes waiting for the segment's end.
class SegmentTracker {
 public:
  SegmentTracker(EncodedBlock& out, const BlockStyle& style)
      : out_(out), style_(style), mq_(out.data), raw_(out.data) {}

  MqEncoder& mq() { return mq_; }
  RawWriter& raw() { return raw_; }

  void begin_pass_if_needed(bool raw) {
    if (open_) return;
    open_ = true;
    if (raw)
      raw_.start();
    else
      mq_.start();
  }

  void pass_done(int pass, bool raw, bool ends_segment) {
    PassInfo& info = out_.passes[static_cast<std::size_t>(pass)];
    if (!ends_segment) {
      pending_.push_back(PendingPass{pass, raw, raw ? MqTruncationPoint{} : mq_.truncation_point(),
                                     raw ? raw_.truncation_point() : RawTruncationPoint{}});
      return;
    }
    if (raw)
      raw_.terminate(style_.predictable_termination);
    else if (style_.predictable_termination)
      mq_.flush_predictable();
    else
      mq_.flush();
    const std::size_t end = out_.data.size();
    // Shortest lengths that still decode every pass up to theirs, given the finished segment.
    // Each is at least the previous pass's (the segment's start for its first pass), so lengths
    // never decrease; the first pass of a block may need no byte at all.
    for (const PendingPass& p : pending_) {
      const std::size_t previous = p.pass > 0 ? out_.passes[static_cast<std::size_t>(p.pass) - 1].length : 0;
      const std::size_t length = p.raw ? minimal_raw_truncation_length(out_.data, p.raw_point, end, previous)
                                       : minimal_truncation_length(out_.data, p.point, end, previous);
      out_.passes[static_cast<std::size_t>(p.pass)].length = std::min(length, end);
    }
    pending_.clear();
    info.length = end;
    info.terminated = true;
    open_ = false;
  }

 private:
  EncodedBlock& out_;
  const BlockStyle& style_;
  MqEncoder mq_;
  RawWriter raw_;
  std::vector<PendingPass> pending_;
  bool open_ = false;
};

// D.5: the symbol 1010 in the UNIFORM context after each cleanup pass lets a decoder detect errors.
void code_segmentation_symbol(ContextSet& cx, MqEncoder& mq) {
  for (int bit : {1, 0, 1, 0}) mq.encode(bit, cx[kUniformContext]);
}

template <bool kMeasure>
double code_pass(int pass, int plane, bool raw, const BlockView& v, const ZeroCodingTable& zc, ContextSet& cx,
                 SegmentTracker& seg, const BlockStyle& style) {
  switch (pass_kind(pass)) {
    case PassKind::Significance:
      return raw ? significance_pass_raw<kMeasure>(v, plane, seg.raw())
                 : significance_pass<kMeasure>(v, plane, zc, cx, seg.mq());
    case PassKind::Refinement:
      return raw ? refinement_pass_raw<kMeasure>(v, plane, seg.raw())
                 : refinement_pass<kMeasure>(v, plane, cx, seg.mq());
    case PassKind::Cleanup:
      break;
  }
  const double gain = cleanup_pass<kMeasure>(v, plane, zc, cx, seg.mq());
  if (style.segmentation_symbols) code_segmentation_symbol(cx, seg.mq());
  return gain;
}

// Coefficients of the block whose highest set bit is `plane`: those that become significant there.
int newly_significant(const BlockView& v, int plane) {
  int count = 0;
  for (int y = 0; y < v.height; ++y) {
    const std::uint32_t* row = v.magnitude + v.index(0, y);
    for (int x = 0; x < v.width; ++x) count += (row[x] >> plane) == 1;
  }
  return count;
}

// Whether one quiet bit-plane (bought `plane_gain`, under the stop rule's slope) is enough to stop.
// A block's plane slopes normally fall about fourfold from one plane to the next, so after a plane
// that paid, the first one that does not marks the decline. Three things break that pattern, and
// each keeps the block going to the two-plane rule: the top planes, before any plane paid (a few
// coefficients, the MQ coder still learning its probabilities); a plane that bought nothing or
// lost (refinement can move a reconstruction away); and a plane below that brings many more new
// coefficients than this one (structured content: an edge or a line whose coefficients all come in
// at one plane), since its fixed cost of coding "nothing here" then spreads over many more gains.
// On the 2048x2048 Kodak mosaic this codes 9 to 11 % fewer instructions than two planes always, and
// gives the same files at 0.1875, 0.75 and 3 bpp. "Many more" is more than four times as many (plus
// four): a plane's count normally about doubles from one plane to the next, while the blocks that
// broke the rule there went from 0 to 64, 1 to 9 and 2 to 45.
//
// Before any plane paid, a plane far below the slope (`slope_ratio`, its slope over the stop
// rule's, under 1 / kUnpaidQuietFactor) ends the block too: an unpaid block's next plane rose at
// most 15.5-fold on the 2048x2048 mosaic (0.076 to 1.17 of the stop slope), so such a block would
// not have paid a plane later either. Most blocks that end up contributing nothing at low rates then
// stop after their top plane instead of coding a second. Measured on the mosaic, 1 thread
// (callgrind): 0.1875 bpp 960 M to 918 M instructions, 0.75 bpp 2.10 G to 1.84 G, the same files at
// 0.1875, 0.75 and 3 bpp. A factor of 16 saved more (908 M, 1.83 G) but cost kodim03 0.004 dB at
// 0.75 bpp against full coding (j2k_lossy_test's pass-skipping case); with 32 the 48 photograph
// cases give the full-coding file in 47 and 0.003 dB more in the other (kodim16 at 0.1875 bpp).
constexpr double kUnpaidQuietFactor = 32;

bool stops_after_quiet_plane(const BlockView& v, int plane, double plane_gain, double slope_ratio,
                             bool paying_plane_seen) {
  if (plane_gain <= 0 || plane == 0) return false;
  if (!paying_plane_seen) return slope_ratio * kUnpaidQuietFactor < 1;
  const int here = newly_significant(v, plane), below = newly_significant(v, plane - 1);
  return below <= 4 * here + 4;
}

// Whether a block of this energy (all the distortion it could ever buy), bought with a single
// byte, would still be worth less than the stop rule's slope: then no hull point of it can reach
// the slope, and no pass is worth coding.
bool worth_no_pass(double energy, const StopRule& stop) {
  return stop.min_slope > 0 && stop.weight * energy < stop.min_slope * kLeastPassBytes;
}

// The coder proper, on a loaded block.
EncodedBlock encode_state(CoefficientState& state, int width, int height, Orientation o, int magnitude_bitplanes,
                          BlockStyle style, StopRule stop, Distortion distortion = Distortion::Measured) {
  validate(stop, distortion);
  const bool measure = distortion == Distortion::Measured;
  const int planes = state.bit_planes();
  if (planes > magnitude_bitplanes)
    throw std::invalid_argument("a coefficient magnitude needs " + std::to_string(planes) + " bit-planes, Mb is " +
                                std::to_string(magnitude_bitplanes));

  EncodedBlock out;
  out.energy = state.energy();
  out.missing_msbs = magnitude_bitplanes - planes;
  out.bit_planes = planes;
  const int count = pass_count(planes);
  if (count > 0 && worth_no_pass(out.energy, stop)) {
    out.stopped_early = true;
    return out;
  }
  out.passes.resize(static_cast<std::size_t>(count));
  if (count == 0) return out;
  // The bytes go to a per-thread buffer that keeps its capacity, and are copied out at their exact
  // size at the end: a fresh width x height reservation per block touched a new page (a fault and
  // a page clear) for each of the thousands of blocks of a large image, most of them coding a few
  // bytes at low rates.
  thread_local std::vector<std::uint8_t> buffer;
  buffer.clear();
  buffer.reserve(static_cast<std::size_t>(width) * static_cast<std::size_t>(height));
  out.data.swap(buffer);

  const BlockView v = state.view(style.vertically_causal);
  const ZeroCodingTable& zc = zero_coding_table(o);
  ContextSet cx;
  reset_contexts(cx);
  SegmentTracker seg(out, style);
  double plane_gain = 0;        // distortion bought by the bit-plane being coded so far
  std::size_t plane_start = 0;  // estimated bytes when it began
  int quiet_planes = 0;         // bit-planes in a row that bought less than stop.min_slope
  bool paying_plane_seen = false;
  for (int pass = 0; pass < count; ++pass) {
    const bool raw = pass_is_raw(pass, style);
    seg.begin_pass_if_needed(raw);
    const int plane = pass_plane(pass, planes);
    const double gain = measure ? code_pass<true>(pass, plane, raw, v, zc, cx, seg, style)
                                : code_pass<false>(pass, plane, raw, v, zc, cx, seg, style);
    out.passes[static_cast<std::size_t>(pass)].distortion_decrease = gain;
    plane_gain += gain;
    bool last = false;
    if (stop.min_slope > 0 && pass + 1 < count && pass_kind(pass) == PassKind::Cleanup) {
      // A cleanup pass is always arithmetic coded, so the MQ coder's state tells the bytes so far.
      const MqTruncationPoint point = seg.mq().truncation_point();
      const std::size_t bytes = point.committed + static_cast<std::size_t>((point.buffered_bits + 7) / 8);
      const double spent = static_cast<double>(std::max<std::size_t>(bytes, plane_start + 1) - plane_start);
      // A bit-plane below the threshold ends the block when stops_after_quiet_plane says one is
      // enough, and two in a row always do.
      const double slope = stop.weight * plane_gain / spent;
      const bool quiet = slope < stop.min_slope;
      quiet_planes = quiet ? quiet_planes + 1 : 0;
      last = quiet_planes >= kQuietPlanesToStop ||
             (quiet && stops_after_quiet_plane(v, plane, plane_gain, slope / stop.min_slope, paying_plane_seen));
      paying_plane_seen = paying_plane_seen || !quiet;
      plane_gain = 0;
      plane_start = bytes;
    }
    if (stop.pass_limit > 0 && pass + 1 >= stop.pass_limit && pass + 1 < count) last = true;
    seg.pass_done(pass, raw, last || pass_ends_segment(pass, count, style));
    if (style.reset) reset_contexts(cx);
    if (last) {
      out.passes.resize(static_cast<std::size_t>(pass) + 1);
      out.stopped_early = true;
      break;
    }
  }
  std::vector<std::uint8_t> exact(out.data.begin(), out.data.end());
  out.data.swap(buffer);
  out.data = std::move(exact);
  return out;
}

}  // namespace

EncodedBlock encode_block(std::span<const std::int32_t> coefficients, int width, int height, Orientation o,
                          int magnitude_bitplanes, BlockStyle style, std::span<const std::uint8_t> fractions,
                          StopRule stop) {
  validate(coefficients, width, height, magnitude_bitplanes);
  if (!fractions.empty() && fractions.size() != coefficients.size())
    throw std::invalid_argument("code-block given " + std::to_string(fractions.size()) + " fractions for " +
                                std::to_string(coefficients.size()) + " coefficients");
  CoefficientState state(coefficients, width, height, fractions);
  return encode_state(state, width, height, o, magnitude_bitplanes, style, stop);
}

EncodedBlock encode_block(const IntegerBlock& block, Orientation o, int magnitude_bitplanes, BlockStyle style,
                          StopRule stop, Distortion distortion) {
  validate_shape(block.origin, block.stride, block.width, block.height, magnitude_bitplanes);
  CoefficientState state(block);
  return encode_state(state, block.width, block.height, o, magnitude_bitplanes, style, stop, distortion);
}

EncodedBlock encode_block(const FloatBlock& block, Orientation o, int magnitude_bitplanes, BlockStyle style,
                          StopRule stop, Distortion distortion) {
  validate_shape(block.origin, block.stride, block.width, block.height, magnitude_bitplanes);
  validate(stop, distortion);
  if (stop.min_slope <= 0) {
    CoefficientState state(block, float_block_planes(block));
    return encode_state(state, block.width, block.height, o, magnitude_bitplanes, style, stop, distortion);
  }
  // At low rates most blocks are worth nothing: tell them by their energy before loading them.
  const FloatBlockSurvey survey = survey_float_block(block);
  const FloatBlockPlanes& planes = survey.planes;
  if (planes.bit_planes > 0 && planes.bit_planes <= magnitude_bitplanes) {
    const double energy = survey.energy;
    if (worth_no_pass(energy, stop)) {
      EncodedBlock out;
      out.energy = energy;
      out.bit_planes = planes.bit_planes;
      out.missing_msbs = magnitude_bitplanes - planes.bit_planes;
      out.stopped_early = true;
      return out;
    }
  }
  CoefficientState state(block, planes);
  return encode_state(state, block.width, block.height, o, magnitude_bitplanes, style, stop, distortion);
}

}  // namespace codec::t1
