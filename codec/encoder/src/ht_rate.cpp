#include "ht_rate.h"

#include <algorithm>
#include <cmath>

#include "codec/rate/hull.h"
#include "codec/rate/selection.h"

namespace codec {
namespace {

// A code-block loaded into this worker's block, which it keeps from block to block: a 64x64
// block's buffers (some 28 KB) are then neither allocated nor cleared for every load (a 1024x1024
// encode at 0.75 bpp loads some 900 blocks, and the clearing was 4 % of its instructions). Valid
// until the worker's next load.
const ht::HtBlock& worker_block(const CodedTile& coded, const BlockJob& job, const EncodeParams& params) {
  thread_local ht::HtBlock block;
  load_ht_block(coded, job, params, block);
  return block;
}

// A cleanup's estimated length in bits: per significant sample about its quad's magnitude bits
// (MagSgn, less what the EMB patterns imply), per significant quad its CxtVLC codeword and U-VLC
// residual, and a fixed part (MEL symbols, stuffing, Scup), at the sample's scale. Fitted by least
// squares to 1,526 cleanups of Kodak photographs 3, 5 and 13 near their cut at 0.25, 0.75 and
// 2 bpp (the coefficients moved by under 3 % between rates): median error 2.4-5.5 %, where
// magnitude bits and quads alone (3 bits a quad, one scale) were 18-28 % off.
constexpr double kBitsPerMagnitudeBit = 0.92;
constexpr double kBitsPerQuad = 6.9;
constexpr double kBitsPerCleanup = 85;

double model_bits(const ht::PlaneStatistics& s) {
  return kBitsPerMagnitudeBit * s.magnitude_bits + kBitsPerQuad * s.significant_quads + kBitsPerCleanup;
}

ht::HtPasses ht_passes(const EncodeParams& params) {
  return params.ht_refinement ? ht::HtPasses::CleanupAndRefinement : ht::HtPasses::Cleanup;
}

// The fewest bytes any HT truncation point has: a cleanup segment ends with Scup, the length of its
// MEL and VLC parts, which is at least 2 (T.814 7.1).
constexpr double kLeastCleanupBytes = 2;
// How far below the model's estimate a cleanup's length is assumed to be able to fall when
// bounding a block's slopes: the model's median error is 2-6 %, its worst seen some 30 %.
constexpr double kModelBytesMargin = 0.5;

// The fewest bytes a cleanup the model gives `bits` could take: kModelBytesMargin of its estimate at
// `bytes_per_bit`, and never under kLeastCleanupBytes. Every bound of a block's slopes divides by it.
double fewest_bytes(double bits, double bytes_per_bit) {
  return std::max(kLeastCleanupBytes, kModelBytesMargin * bytes_per_bit * bits);
}

// An upper bound of the slope of any truncation point of a block, from its plane statistics: a
// cleanup on plane p buys energy - error(p), and with its refinement passes at most what the
// cleanup on p - 1 buys, for no fewer bytes than half the model's estimate of the cleanup on p
// (and never under 2). A block whose bound is below the threshold is not coded.
double slope_bound(const std::vector<ht::PlaneStatistics>& stats, double weight, double bytes_per_bit) {
  const int planes = static_cast<int>(stats.size()) - 1;
  const double energy = stats.back().error;
  double bound = 0;
  for (int p = planes - 1; p >= 0; --p) {
    const double bytes = fewest_bytes(model_bits(stats[static_cast<std::size_t>(p)]), bytes_per_bit);
    const double bought = energy - stats[static_cast<std::size_t>(std::max(0, p - 1))].error;
    bound = std::max(bound, weight * bought / bytes);
  }
  return bound;
}

// The fewest bytes the model gives any truncation point of a block, at the margin slope_bound
// allows: a coded plane has at least one significant quad, with a magnitude bit.
double least_point_bytes(double bytes_per_bit) {
  return fewest_bytes(kBitsPerMagnitudeBit + kBitsPerQuad + kBitsPerCleanup, bytes_per_bit);
}

// Below which plane a block's plane errors need not be known at `threshold`: the plane where the
// cleanup, on the model's lengths (at kModelBytesMargin of them, as slope_bound), would buy less
// than kUsefulSlope times the threshold per byte even were it to buy the block's whole energy (no
// more than `energy_bound`). A point on the hull buys at least its own hull slope per byte from
// nothing, so such planes' points lie far below the threshold; the per-plane errors, the costliest
// statistics, are summed only from there up (on the 2048x2048 mosaic at 0.75 bpp, 1.4 % fewer
// instructions).
constexpr double kUsefulSlope = 0.25;
int lowest_useful_plane(const std::vector<ht::PlaneStatistics>& counts, double energy_bound, double weight,
                        double threshold, double bytes_per_bit) {
  const int planes = static_cast<int>(counts.size()) - 1;
  const double most_bytes = energy_bound * weight / (kUsefulSlope * threshold);
  for (int p = planes - 1; p >= 0; --p) {
    if (fewest_bytes(model_bits(counts[static_cast<std::size_t>(p)]), bytes_per_bit) > most_bytes) return p;
  }
  return 0;
}

// A block's cleanups as estimated truncation points, highest plane first (as truncation_points
// orders the coded ones): lengths from the model, distortion decreases from the plane statistics'
// error estimates.
std::vector<t1::PassInfo> estimated_points(const std::vector<ht::PlaneStatistics>& stats, double bytes_per_bit) {
  const int planes = static_cast<int>(stats.size()) - 1;
  std::vector<t1::PassInfo> points;
  std::size_t previous = 0;
  for (int p = planes - 1; p >= 0; --p) {
    const auto& s = stats[static_cast<std::size_t>(p)];
    const auto bytes = std::max(previous, static_cast<std::size_t>(std::ceil(bytes_per_bit * model_bits(s))));
    points.push_back(t1::PassInfo{bytes, stats[static_cast<std::size_t>(p) + 1].error - s.error, true});
    previous = bytes;
  }
  return points;
}

// How near the threshold the slope of the estimated hull's first refused point must come for the
// cleanup of the plane below the estimated one to be coded as well. It had been coded always, the
// finest and costliest of a block's three, yet on the 2048x2048 mosaic at 0.75 bpp the allocation
// took it for 2 of some 1,000 blocks. Never coding it left more blocks to extend (two planes each)
// and cost 9 % more instructions on the 1024x1024 mosaic; 0.7 took 4 % fewer there, and on the
// 2048x2048 one 2.8 %, 10 % and 22 % fewer at 0.1875, 0.75 and 3 bpp, with the same PSNR. Every
// HT rate test case kept its PSNR within 0.001 dB (at 0.9, kodim03 at 0.75 bpp lost 0.004 dB).
constexpr double kBelowReach = 0.7;

// How steep the estimated hull's step to the estimated plane's cleanup must be, against the
// threshold, for the cleanup of the plane above it to be left uncoded: the allocation then takes
// the estimated plane (or a finer one) unless the estimate is off by that factor. The plane above
// had been coded always, yet on the 4096x4096 mosaic at 0.75 bpp the allocation took it for some
// 290 of 5,000 blocks. After the allocation such a block is extended upwards only where its
// estimated step falls short of kAboveReach times the lowest slope taken (ht_blocks_at_edges).
// On the 2048x2048 mosaic at 0.75 bpp, 9.2 % fewer instructions (0.1875 bpp: 2.4 % fewer; 3 bpp:
// 0.4 % more, from more extensions) for 0.0025 dB (34.5918 to 34.5893 dB, the same bytes); on the
// 16 photographs the mean PSNR moved by -0.0002, -0.0003 and -0.0013 dB at 0.25, 0.75 and 2 bpp.
// At 1.5, 1100 M instructions and 0.0029 dB less; at 3, 2 % fewer instructions.
// Since the twenty-third session such a block's plane below is left uncoded too: on the 2048x2048
// mosaic at 0.75 bpp the allocation had taken it for none of the 272 blocks it was coded for (the
// estimated plane's cleanup for 253 of them, with its SigProp pass for 19). A 1-thread encode
// takes 1,159 M to 1,023 M instructions (-11.7 %) at 0.75 bpp, 988 M to 977 M at 0.1875 bpp and
// 2,069 M to 2,071 M at 3 bpp, for 34.7145 and 27.8497 dB as before and 46.4562 dB instead of
// 46.4563; the 16 photographs' mean PSNR moved by +0.0003, +0.0002 and -0.0001 dB at 0.25, 0.75
// and 2 bpp, no photograph by more than -0.0007 dB. (Leaving it out wherever the step is 1.5
// times the threshold took 0.4 % fewer still, for photographs within -0.0038 dB.)
constexpr double kAboveReach = 2;

// The plane below passes kBelowReach on the estimate alone; it is coded only where, once the
// estimated plane's codeword is coded, the plane below's cleanup could still be worth this much of
// the threshold from one of that codeword's points: its length is the model's, scaled by what the
// model missed on the estimated plane's cleanup in this block, and its distortion the statistics'
// estimate. On the 2048x2048 mosaic at 0.75 bpp, 3.6 % fewer instructions (1,023 M to 986 M), the
// same PSNR (34.5894 dB); the 16 photographs' mean PSNR moved by +0.0000, +0.0005 and +0.0000 dB
// at 0.25, 0.75 and 2 bpp, no photograph by more than -0.0013 dB (kodim14 at 0.75 bpp). At 0.8,
// 5.0 % fewer, but kodim15 lost 0.0057 dB at 0.25 bpp.
constexpr double kBelowCalibrated = 0.75;

bool plane_below_may_pay(const HtCandidates& c, const std::vector<ht::PlaneStatistics>& stats, int plane, double weight,
                         double threshold, double bytes_per_bit) {
  const t1::EncodedBlock& coded = *c.by_plane[static_cast<std::size_t>(plane)];
  const auto at = [&](int p) -> const ht::PlaneStatistics& { return stats[static_cast<std::size_t>(p)]; };
  const double model_error = static_cast<double>(coded.passes.front().length) / (bytes_per_bit * model_bits(at(plane)));
  const double below_bytes = model_error * bytes_per_bit * model_bits(at(plane - 1));
  const double below_gain = stats.back().error - at(plane - 1).error;  // from nothing, as the passes' sums
  double gain = 0, best = 0;
  for (const t1::PassInfo& pass : coded.passes) {
    gain += pass.distortion_decrease;
    const auto bytes = static_cast<double>(pass.length);
    if (below_bytes > bytes) best = std::max(best, weight * (below_gain - gain) / (below_bytes - bytes));
  }
  return best >= kBelowCalibrated * threshold;
}

// Where the estimate cuts a block at `threshold`: the plane whose cleanup its hull takes (-1: none),
// and the slope of the hull's next point, the first it refuses (0: none).
struct EstimatedCut {
  int plane = -1;
  double next_slope = 0;
  double slope = 0;  // of the hull's step to `plane`'s cleanup
};

EstimatedCut estimated_cut(const std::vector<ht::PlaneStatistics>& stats, double weight, double threshold,
                           double bytes_per_bit) {
  const int planes = static_cast<int>(stats.size()) - 1;
  const std::vector<rate::HullPoint> hull = rate::convex_hull(estimated_points(stats, bytes_per_bit), weight);
  const std::size_t points = rate::points_at_or_above(hull, threshold);
  return EstimatedCut{points == 0 ? -1 : planes - hull[points - 1].passes,
                      points < hull.size() ? hull[points].slope : 0.0, points == 0 ? 0.0 : hull[points - 1].slope};
}

// The plane whose cleanup the estimate takes at `threshold`; -1: none.
int estimated_plane(const std::vector<ht::PlaneStatistics>& stats, double weight, double threshold,
                    double bytes_per_bit) {
  return estimated_cut(stats, weight, threshold, bytes_per_bit).plane;
}

// The threshold at which the length model, at `bytes_per_bit`, has a sample of blocks (scaled up)
// spend the target's bytes or leave its error: a guess made before any of them is coded.
double model_threshold(const std::vector<BlockJob>& jobs, const BlockSample& sample,
                       const std::vector<std::vector<ht::PlaneStatistics>>& stats, double bytes_per_bit,
                       const Tier1Target& target) {
  std::vector<std::vector<rate::HullPoint>> hulls(sample.blocks.size());
  double energy = 0;
  for (std::size_t k = 0; k < sample.blocks.size(); ++k) {
    const double weight = jobs[sample.blocks[k]].weight;
    if (stats[k].size() > 1) hulls[k] = rate::convex_hull(estimated_points(stats[k], bytes_per_bit), weight);
    energy += sample.scale[k] * stats[k].back().error * weight;
  }
  return threshold_for_target(hulls, sample.scale, energy, target);
}

// The most blocks of one resolution the sample takes (and the presample a quarter of that): one in
// kSampleStride up to 2,304 blocks, as the 2048x2048 mosaic's finest resolution has, fewer beyond:
// the prediction's accuracy follows the blocks sampled. The 4096x4096 mosaic's finest resolution
// (9,216 blocks) is then sampled one in 64 and its next (2,304) one in 16: at 0.75 bpp, 7.3 %
// fewer instructions (4,087 M to 3,787 M), 35.1474 dB instead of 35.1475 dB (28 bytes fewer) and
// fewer blocks extended (357 against 539); at 0.1875 bpp the same file, at 3 bpp 0.003 dB more,
// and the 30 and 38 dB targets land 0.001 dB higher for 86 and 279 more bytes. Photographs and
// images up to 2048x2048 sample as before. (Sampling one in 32 throughout had cost the 2048x2048
// mosaic 8.6 % more instructions and 0.005 dB: 183 more blocks extended.)
constexpr std::size_t kHtSampledPerResolution = 144;

// The step's phase (ht_uniform_step_octaves) is estimated from the middle kPhaseRows rows of up to
// kPhaseSampledPerResolution blocks of each resolution, scattered (sample_blocks): the length model
// is summed over many blocks, a part of each, rather than over a few whole ones, because the
// crossing must be known to some 0.05 of an octave and a few blocks carry much of a tile's bytes.
// On the 2048x2048 mosaic at 0.75 bpp, 64 whole blocks per resolution put it anywhere from 6.58 to
// 7.04 octaves as the sample's place moved (the crossing of real uniform encodes: 6.94), and a
// tenth of an octave off costs 0.05 dB there. Every block's middle 16 rows gave 6.96; 8 rows left
// up to 0.25 octaves' error on single photographs, 32 cost twice the time for little more. 384
// blocks instead of 768 took 7 % fewer instructions at 0.1875 bpp on that mosaic, for 0.0055 dB
// less there at 0.1875 and 0.75 bpp.
constexpr int kPhaseRows = 16;
constexpr std::size_t kPhaseSampledPerResolution = 768;

// The model's scale were it exact: a byte per 8 bits.
constexpr double kNominalBytesPerModelBit = 1.0 / 8;

std::vector<int> planes_between(int lowest, int highest) {
  std::vector<int> out;
  for (int p = highest; p >= lowest; --p) out.push_back(p);
  return out;
}

// The sample's cleanups near where the prediction cuts each block (two planes either side), for
// the model's scale: bytes per model bit (1/8 if the model were exact).
double bytes_per_model_bit(const CodedTile& coded, const std::vector<std::size_t>& sample,
                           const std::vector<std::vector<ht::PlaneStatistics>>& stats, double threshold) {
  double bytes = 0, bits = 0;
  for (std::size_t k = 0; k < sample.size(); ++k) {
    const std::size_t b = sample[k];
    const HtCandidates& c = coded.ht_candidates[b];
    const t1::EncodedBlock& points = coded.blocks[b];
    const std::vector<rate::HullPoint> hull = rate::convex_hull(points.passes, coded.jobs[b].weight);
    const std::size_t taken = rate::points_at_or_above(hull, threshold);
    const int cut = taken == 0 ? points.bit_planes - 1 : c.point(hull[taken - 1].passes).plane;
    for (int p = std::max(0, cut - 2); p <= std::min(points.bit_planes - 1, cut + 2); ++p) {
      const auto& candidate = c.by_plane[static_cast<std::size_t>(p)];
      if (!candidate) continue;  // a plane the two-step sample left out
      const ht::PlaneStatistics& s = stats[k][static_cast<std::size_t>(p)];
      bytes += static_cast<double>(candidate->passes[0].length);  // the cleanup's, which the model estimates
      bits += model_bits(s);
    }
  }
  return bits > 0 ? bytes / bits : 1.0 / 8;
}

}  // namespace

void code_ht_candidates(CodedTile& coded, const EncodeParams& params, const Tier1Target& target, base::ThreadPool& pool,
                        const std::function<void()>& block_done) {
  const std::size_t n = coded.jobs.size();
  coded.ht_candidates.assign(n, HtCandidates{});
  // The cleanups of the listed blocks from the planes `planes_of` names (given the block's plane
  // statistics), with their truncation points; the statistics are kept where asked for. A block
  // coded again keeps what it had and gains the planes it lacked.
  using PlanesOf = std::function<std::vector<int>(std::size_t block, const std::vector<ht::PlaneStatistics>&)>;
  auto code_planes = [&](const std::vector<std::size_t>& which, const PlanesOf& planes_of,
                         std::vector<std::vector<ht::PlaneStatistics>>* stats) {
    if (stats) stats->assign(which.size(), {});
    pool.parallel_for(which.size(), [&](std::size_t k) {
      const std::size_t b = which[k];
      const ht::HtBlock& block = worker_block(coded, coded.jobs[b], params);
      std::vector<ht::PlaneStatistics> s = ht::plane_statistics(block);
      add_candidates(coded.ht_candidates[b], block, planes_of(b, s), ht_passes(params));
      coded.blocks[b] = truncation_points(coded.ht_candidates[b], block.bit_planes, s.back().error);
      if (stats) (*stats)[k] = std::move(s);
    });
  };
  const PlanesOf every_plane = [](std::size_t, const std::vector<ht::PlaneStatistics>& s) {
    return planes_between(0, static_cast<int>(s.size()) - 2);
  };
  std::vector<std::size_t> all(n);
  for (std::size_t i = 0; i < n; ++i) all[i] = i;
  if (target.kind == Tier1Target::Kind::None || target.value <= 0 || n < 64) {
    code_planes(all, every_plane, nullptr);
    for (std::size_t i = 0; i < n; ++i) block_done();
    return;
  }
  // The sample predicts the threshold in two steps, as EBCOT's pass skipping does (tile_coder.h):
  // the sparser presample gives a first estimate, and the rest of the sample is coded from the plane
  // above the one the length model puts at that estimate down to the plane it puts at an eighth of
  // it, and one more. Its lowest planes, the costliest cleanups (the most significant samples), are
  // left out, and so are its top planes, whose slopes lie far above any threshold the prediction
  // can reach: their hull step is the plane below's with them in it (and should the threshold rise
  // above it after all, the extension after the allocation codes them). The
  // presample itself (which holds the lowest resolutions whole, blocks of many planes) is coded
  // alike, down from a guess: the threshold at which the model, at its nominal scale, has the
  // presample meet the target. Should a prediction fall within reach of where its blocks stop,
  // they are coded from every plane after all and it is made again.
  const BlockSample sample = sample_blocks(coded.jobs, kSampleStride, kHtSampledPerResolution);
  const BlockSample presample =
      sample_blocks(coded.jobs, kPresampleStride, kHtSampledPerResolution * kSampleStride / kPresampleStride);
  std::vector<bool> in_presample(n);
  for (std::size_t i : presample.blocks) in_presample[i] = true;
  std::vector<std::size_t> sample_rest;
  for (std::size_t i : sample.blocks)
    if (!in_presample[i]) sample_rest.push_back(i);
  // Down to the plane the model, at `bytes_per_bit`, puts at `reach`, and one more; from the plane
  // above the one it puts at kPresampleMargin times `reach` (on the 2048x2048 mosaic at 0.75 bpp,
  // 1.5 % fewer instructions; the files at 0.1875, 0.75 and 3 bpp the same, the 38 dB one 112
  // bytes smaller at 38.0894 dB instead of 38.0885 dB).
  auto planes_down_to = [&](double reach, double bytes_per_bit) -> PlanesOf {
    return [&coded, reach, bytes_per_bit](std::size_t b, const std::vector<ht::PlaneStatistics>& s) {
      const int top = static_cast<int>(s.size()) - 2;
      if (top < 0) return std::vector<int>{};
      const double weight = coded.jobs[b].weight;
      const int cut = estimated_plane(s, weight, reach, bytes_per_bit);
      const int high = estimated_plane(s, weight, reach * kPresampleMargin, bytes_per_bit);
      return planes_between(cut < 0 ? top : std::max(0, cut - 1), high < 0 ? top : std::min(top, high + 1));
    };
  };
  // The presample's blocks stay loaded until the prediction is made (it is few blocks).
  std::vector<ht::HtBlock> presample_blocks(presample.blocks.size());
  std::vector<std::vector<ht::PlaneStatistics>> presample_stats(presample.blocks.size()), rest_stats;
  pool.parallel_for(presample.blocks.size(), [&](std::size_t k) {
    load_ht_block(coded, coded.jobs[presample.blocks[k]], params, presample_blocks[k]);
    presample_stats[k] = ht::plane_statistics(presample_blocks[k]);
  });
  // The blocks with the most coding (planes times samples) go first: the presample holds a few big
  // low-resolution blocks of many planes, and in sample order those of the last component started
  // last, to finish alone.
  auto code_presample = [&](const PlanesOf& planes_of) {
    std::vector<std::vector<int>> planes(presample.blocks.size());
    std::vector<std::size_t> order(presample.blocks.size());
    std::vector<std::size_t> work(presample.blocks.size());
    for (std::size_t k = 0; k < planes.size(); ++k) {
      const std::size_t b = presample.blocks[k];
      planes[k] = planes_of(b, presample_stats[k]);
      order[k] = k;
      work[k] = planes[k].size() * static_cast<std::size_t>(coded.jobs[b].width) *
                static_cast<std::size_t>(coded.jobs[b].height);
    }
    std::stable_sort(order.begin(), order.end(), [&](std::size_t x, std::size_t y) { return work[x] > work[y]; });
    pool.parallel_for(order.size(), [&](std::size_t w) {
      const std::size_t k = order[w];
      const std::size_t b = presample.blocks[k];
      add_candidates(coded.ht_candidates[b], presample_blocks[k], planes[k], ht_passes(params));
      coded.blocks[b] =
          truncation_points(coded.ht_candidates[b], presample_blocks[k].bit_planes, presample_stats[k].back().error);
    });
  };
  const double guess = model_threshold(coded.jobs, presample, presample_stats, kNominalBytesPerModelBit, target);
  code_presample(planes_down_to(guess / kPresampleMargin, kNominalBytesPerModelBit));
  double first_estimate = predict_threshold(coded.jobs, coded, presample, target);
  bool presample_whole = false;
  if (first_estimate < guess / (kPresampleMargin / 2)) {
    code_presample(every_plane);
    presample_whole = true;
    first_estimate = predict_threshold(coded.jobs, coded, presample, target);
  }
  const double first_bytes_per_bit = bytes_per_model_bit(coded, presample.blocks, presample_stats, first_estimate);
  code_planes(sample_rest, planes_down_to(first_estimate / kPresampleMargin, first_bytes_per_bit), &rest_stats);
  double threshold = predict_threshold(coded.jobs, coded, sample, target);
  const bool rest_too_shallow = threshold < first_estimate / (kPresampleMargin / 2);
  const bool presample_too_shallow = !presample_whole && threshold < guess / (kPresampleMargin / 2);
  if (rest_too_shallow || presample_too_shallow) {
    if (rest_too_shallow) code_planes(sample_rest, every_plane, nullptr);
    if (presample_too_shallow) code_presample(every_plane);
    threshold = predict_threshold(coded.jobs, coded, sample, target);
  }
  presample_blocks.clear();
  coded.stop_threshold = threshold;
  // The sample's statistics in its order, for the length model's scale.
  std::vector<std::vector<ht::PlaneStatistics>> sample_stats;
  {
    std::size_t next_presample = 0, next_rest = 0;
    for (std::size_t i : sample.blocks)
      sample_stats.push_back(std::move(in_presample[i] ? presample_stats[next_presample++] : rest_stats[next_rest++]));
  }
  const double bytes_per_bit = bytes_per_model_bit(coded, sample.blocks, sample_stats, threshold);
  coded.ht_bytes_per_model_bit = bytes_per_bit;
  for (std::size_t i = 0; i < sample.blocks.size(); ++i) block_done();

  std::vector<bool> in_sample(n);
  for (std::size_t i : sample.blocks) in_sample[i] = true;
  std::vector<std::size_t> rest;
  for (std::size_t i : all)
    if (!in_sample[i]) rest.push_back(i);
  pool.parallel_for(rest.size(), [&](std::size_t k) {
    const std::size_t b = rest[k];
    const BlockJob& job = coded.jobs[b];
    HtCandidates& c = coded.ht_candidates[b];
    // A block whose whole energy, bought with the fewest bytes any of its points could take, is worth
    // less than the threshold has every slope_bound below it too: it is skipped (or left empty, with
    // no bit-plane) on a survey of its coefficients (their largest magnitude and their energy, in one
    // read), without being quantised and counted. On the 4096x4096 mosaic at 0.75 bpp, 4,565 of the
    // 5,401 blocks skipped. Its slope bound stays the looser one until the check after the
    // allocation needs it (ht_blocks_at_edges).
    if (!params.lossless) {
      const t1::FloatBlockSurvey survey = t1::survey_float_block(float_block(coded, job));
      const double bound = job.weight * survey.energy / least_point_bytes(bytes_per_bit);
      if (survey.planes.bit_planes == 0 || bound < threshold) {
        c.skipped = survey.planes.bit_planes > 0;
        c.slope_bound = bound;
        c.bound_from_energy = true;
        coded.blocks[b] = truncation_points(c, survey.planes.bit_planes, survey.energy);
        block_done();
        return;
      }
    }
    const ht::HtBlock& block = worker_block(coded, job, params);
    std::vector<ht::PlaneStatistics> stats = ht::plane_counts(block);
    ht::add_plane_errors(block, stats,
                         lowest_useful_plane(stats, block.energy_bound, job.weight, threshold, bytes_per_bit));
    const double energy = stats.back().error;
    if (block.bit_planes > 0 && (c.slope_bound = slope_bound(stats, job.weight, bytes_per_bit)) < threshold) {
      // None of its points could be worth the threshold.
      c.skipped = true;
    } else if (block.bit_planes > 0) {
      const int top = block.bit_planes - 1;
      // The estimated plane; the one above it unless the estimated step to the estimated plane is
      // steep (kAboveReach); the one below only where that step is not steep, the estimated hull's
      // next point comes near the threshold (kBelowReach) and, with the estimated plane coded, it
      // still may (kBelowCalibrated). What is left out is left to the extension after the
      // allocation (ht_blocks_at_edges).
      const EstimatedCut cut = estimated_cut(stats, job.weight, threshold, bytes_per_bit);
      const bool leave_above = cut.plane >= 0 && cut.plane < top && cut.slope >= kAboveReach * threshold;
      const int lowest =
          !leave_above && cut.plane > 0 && cut.next_slope >= kBelowReach * threshold ? cut.plane - 1 : cut.plane;
      if (leave_above) {
        c.above_left_plane = cut.plane;
        c.above_left_slope = cut.slope;
      }
      const int highest = leave_above ? cut.plane : std::min(top, cut.plane + 1);
      if (cut.plane < 0) {
        add_candidates(c, block, std::vector<int>{top}, ht_passes(params));
        c.estimated_nothing = true;
      } else {
        add_candidates(c, block, planes_between(cut.plane, highest), ht_passes(params));
        if (lowest < cut.plane && plane_below_may_pay(c, stats, cut.plane, job.weight, threshold, bytes_per_bit))
          add_candidates(c, block, std::vector<int>{lowest}, ht_passes(params));
      }
    }
    coded.blocks[b] = truncation_points(c, block.bit_planes, energy);
    block_done();
  });
}

std::optional<double> ht_uniform_step_octaves(const CodedTile& coded, const EncodeParams& params,
                                              const Tier1Target& target, base::ThreadPool& pool) {
  if (target.kind != Tier1Target::Kind::Bytes || target.value <= 0) return std::nullopt;
  const BlockSample sample = sample_blocks(coded.jobs, 1, kPhaseSampledPerResolution, true);
  // Each sampled block's cleanup bytes on every plane it has, as the length model at its nominal
  // scale puts them, from its middle rows (the counts scaled to the whole block; none where nothing
  // is significant: such a block is left out of the packets).
  std::vector<std::vector<double>> bytes(sample.blocks.size());
  pool.parallel_for(sample.blocks.size(), [&](std::size_t k) {
    BlockJob rows = coded.jobs[sample.blocks[k]];
    const int kept = std::min(rows.height, kPhaseRows);
    const double scale = static_cast<double>(rows.height) / kept;
    rows.y0 += ((rows.height - kept) / 2) & ~1;  // an even row: the quads stay the block's
    rows.height = kept;
    const ht::HtBlock& block = worker_block(coded, rows, params);
    const std::vector<ht::PlaneStatistics> counts = ht::plane_counts(block);
    for (int p = 0; p < block.bit_planes; ++p) {
      const ht::PlaneStatistics& s = counts[static_cast<std::size_t>(p)];
      const double bits =
          scale * (kBitsPerMagnitudeBit * s.magnitude_bits + kBitsPerQuad * s.significant_quads) + kBitsPerCleanup;
      bytes[k].push_back(s.significant_quads > 0 ? kNominalBytesPerModelBit * bits : 0.0);
    }
  });
  std::vector<double> total;  // the tile's, per plane
  for (std::size_t k = 0; k < bytes.size(); ++k) {
    if (total.size() < bytes[k].size()) total.resize(bytes[k].size());
    for (std::size_t p = 0; p < bytes[k].size(); ++p) total[p] += sample.scale[k] * bytes[k][p];
  }
  if (total.empty() || total[0] < target.value) return std::nullopt;
  std::size_t p = 0;
  while (p + 1 < total.size() && total[p + 1] >= target.value) ++p;
  if (p + 1 == total.size() || total[p + 1] <= 0) return static_cast<double>(p);
  // Between two planes the bytes fall about geometrically with the step (on the photographs, real
  // uniform encodes interpolated so land within 0.02 octaves of where the bytes cross).
  return static_cast<double>(p) + std::log(total[p] / target.value) / std::log(total[p] / total[p + 1]);
}

// Where a block the estimate took nothing of, but the allocation takes, is estimated again: at the
// lowest slope taken, but no lower than the predicted threshold divided by this (ht_blocks_at_edges).
constexpr double kReestimateReach = 4;

// A skipped block (its slope bound below the predicted threshold) is extended after an allocation
// only where the bound reaches the lowest slope the allocation takes and the predicted threshold
// divided by this. The lowest slope taken is that of the small steps that fill the bytes left after
// the last whole one, and with the step's phase it fell far below the threshold (the 2048x2048
// mosaic at 0.1875 bpp: 406 skipped blocks extended, against none at the fixed step). At 1.5 a
// 1-thread encode of that mosaic takes 13 % fewer instructions at 0.1875 bpp (1,026 M to 889 M) and
// 3.4 % fewer at 0.75 bpp (1,060 M to 1,024 M), and every file tried is the same: the mosaic at
// 0.1875, 0.75 and 3 bpp with and without the phase, the 4096x4096 one at 0.75 bpp, the 16
// photographs at 0.25, 0.75 and 2 bpp. At 1 (none extended in those encodes), 16 % and 7.6 %
// fewer, for the same files; 1.5 keeps the check for a prediction a little high.
constexpr double kSkippedReach = 1.5;

std::vector<HtExtension> ht_blocks_at_edges(std::vector<CodedTile>& tiles, const LayerPasses& passes,
                                            double lowest_slope, const EncodeParams& params, base::ThreadPool& pool) {
  std::vector<HtExtension> out;
  for (std::size_t t = 0; t < tiles.size(); ++t) {
    if (tiles[t].ht_candidates.empty()) continue;
    // Each block's planes to code, found in parallel, then gathered in block order.
    std::vector<std::vector<int>> planes(tiles[t].blocks.size());
    pool.parallel_for(tiles[t].blocks.size(), [&](std::size_t b) {
      HtCandidates& c = tiles[t].ht_candidates[b];
      const t1::EncodedBlock& points = tiles[t].blocks[b];
      const int top = points.bit_planes - 1;
      if (top < 0) return;
      std::vector<int>& wanted = planes[b];
      if (c.skipped) {
        // The bound must reach the lowest slope taken and, since the twentieth session, a
        // kSkippedReach-th of the predicted threshold (stop_threshold).
        const double skip_floor = std::max(lowest_slope, tiles[t].stop_threshold / kSkippedReach);
        if (c.slope_bound >= skip_floor && c.bound_from_energy) {
          // Bounded now as the blocks loaded in the first place were, so that the same blocks are coded.
          const CodedTile& coded = tiles[t];
          c.slope_bound = slope_bound(ht::plane_statistics(worker_block(coded, coded.jobs[b], params)),
                                      coded.jobs[b].weight, coded.ht_bytes_per_model_bit);
          c.bound_from_energy = false;
        }
        if (c.slope_bound >= skip_floor) {
          wanted = planes_between(std::max(0, top - 1), top);
          c.estimated_nothing = true;
        }
      } else if ((c.estimated_nothing || c.lowest_coded() == top) && !c.estimated_again && passes[t][b].back() > 0) {
        // Taken though the estimate took nothing of it (only its top planes coded): the estimate
        // was off for this block, so it is estimated again, once, where the allocation reached, and
        // the planes about that cut are coded. The rules below would move it a plane a round, and
        // not at all where it refuses its top cleanup's refinement passes. With the step's phase
        // (ht_aligned_base_step) many blocks' steps lie close to the threshold and the prediction
        // misses more of them: on kodim03 at 0.75 bpp two blocks chose their top cleanup (plane 9)
        // where coding every plane chose planes 6 and 7, 0.046 dB behind it; with this rule the
        // file is the one coding every plane gives. Where the allocation reached is the lowest
        // slope it takes, but no lower than a quarter of the predicted threshold: the bytes left
        // after the last whole step are filled with small, shallow ones, and at 2 bpp the lowest
        // slope taken lay 60 times below it (kodim03: planes 1 to 3 coded where 4 was wanted).
        c.estimated_again = true;
        const CodedTile& coded = tiles[t];
        const double reached = std::max(lowest_slope, coded.stop_threshold / kReestimateReach);
        const int cut = estimated_plane(ht::plane_statistics(worker_block(coded, coded.jobs[b], params)),
                                        coded.jobs[b].weight, reached, coded.ht_bytes_per_model_bit);
        if (cut >= 0)
          for (const int p : planes_between(std::max(0, cut - 1), std::min(top, cut + 1)))
            if (!c.by_plane[static_cast<std::size_t>(p)]) wanted.push_back(p);
      } else {
        const int k = passes[t][b].back();
        const int highest = c.highest_coded(), lowest = c.lowest_coded();
        // Above: where the choice is nothing, or the highest cleanup alone. A choice of its SigProp
        // (and MagRef) pass too wants no coarser plane: the allocation took that cleanup whole and
        // more of the plane below it. On the 2048x2048 mosaic at 3 bpp, leaving them out took the
        // blocks extended from 822 to 64 and moved that file by 0.0002 dB (46.3674 to 46.3672); the
        // files at 0.1875 and 0.75 bpp and every HT rate test case stayed the same.
        // Not where the plane above was left uncoded and the estimated step to the choice is still
        // steep at the allocation's lowest slope (kAboveReach). Where it was left uncoded and is
        // wanted now, that one plane: the estimate put the choice there by a margin. With the
        // step's phase (ht_uniform_step_octaves) many blocks' steps to their plane lie close
        // together, and the prediction can fall short of the lowest slope taken (4096x4096 mosaic
        // at 0.75 bpp: 761 against 959) so that 1,524 such blocks were extended; one plane each
        // instead of two gave the same files there, on the 2048x2048 mosaic at 0.1875, 0.75 and
        // 3 bpp and on the 16 photographs at 0.25, 0.75 and 2 bpp, some 2 % faster at 4096x4096.
        const bool left_above = highest == c.above_left_plane;
        const bool above_refused = left_above && c.above_left_slope >= kAboveReach * lowest_slope;
        if ((k == 0 || (c.point(k).plane == highest && c.point(k).passes == 1 && !above_refused)) && highest < top)
          for (const int p : planes_between(highest + 1, std::min(top, highest + (left_above ? 1 : 2))))
            wanted.push_back(p);
        // Below: where the choice takes the lowest cleanup's refinement passes, or is its last point.
        // A choice of that cleanup alone, its refinement passes refused, wants no finer plane: on the
        // 1024x1024 mosaic at 0.75 bpp such extensions were 138 of 185, and leaving them out gave
        // the same files there and in every HT rate test case (0.954 G to 0.833 G instructions).
        const bool refinement_refused =
            k > 0 && c.point(k).passes == 1 && k < static_cast<int>(c.points.size()) && c.point(k + 1).plane == lowest;
        // One plane (seventeenth session; it had been two): on the 4096x4096 mosaic at 0.75 bpp,
        // 3.0 % fewer instructions for the same file and as many blocks extended (2048x2048: 1.2 %
        // fewer, the same files at 0.1875 to 3 bpp and 30 and 38 dB); the photographs' mean PSNR
        // at 0.75 bpp 0.0002 dB lower (kodim06 0.0021 dB), the same at 0.25 and 2 bpp.
        if (k > 0 && c.point(k).plane == lowest && lowest > 0 && !refinement_refused) wanted.push_back(lowest - 1);
      }
    });
    for (std::size_t b = 0; b < planes.size(); ++b)
      if (!planes[b].empty()) out.push_back(HtExtension{t, b, std::move(planes[b])});
  }
  return out;
}

void extend_ht_candidates(std::vector<CodedTile>& tiles, const std::vector<HtExtension>& extensions,
                          const EncodeParams& params, base::ThreadPool& pool) {
  pool.parallel_for(extensions.size(), [&](std::size_t k) {
    const HtExtension& e = extensions[k];
    CodedTile& coded = tiles[e.tile];
    const ht::HtBlock& block = worker_block(coded, coded.jobs[e.block], params);
    HtCandidates& c = coded.ht_candidates[e.block];
    add_candidates(c, block, e.planes, ht_passes(params));
    t1::EncodedBlock& points = coded.blocks[e.block];
    const int missing_msbs = points.missing_msbs;  // the block's, settled by the encoder
    points = truncation_points(c, block.bit_planes, points.energy);
    points.missing_msbs = missing_msbs;
    sync_missing_msbs(c, points);
  });
}

void sync_ht_missing_msbs(std::vector<CodedTile>& tiles, base::ThreadPool& pool) {
  for (CodedTile& coded : tiles)
    pool.parallel_for(coded.ht_candidates.size(),
                      [&](std::size_t b) { sync_missing_msbs(coded.ht_candidates[b], coded.blocks[b]); });
}

void settle_ht_choices(std::vector<CodedTile>& tiles, LayerPasses& passes, base::ThreadPool& pool) {
  for (std::size_t t = 0; t < tiles.size(); ++t) {
    CodedTile& coded = tiles[t];
    if (coded.ht_candidates.empty()) continue;
    // In parallel, the candidates freed by each block's worker too: on the H200 machine's 16
    // threads, one thread freeing a 4096x4096 encode's candidates (several allocations for each of
    // its 12,288 blocks, made on the other threads) took 7-9 ms; on the pool, 3.3 ms.
    pool.parallel_for(coded.blocks.size(), [&](std::size_t b) {
      std::vector<int>& plan = passes[t][b];
      HtCandidates& candidates = coded.ht_candidates[b];
      const int k = plan.empty() ? 0 : plan.back();
      const int kept = k > 0 ? candidates.point(k).passes : 0;
      if (k > 0) {
        const int plane = candidates.point(k).plane;
        t1::EncodedBlock& chosen = coded.blocks[b];
        chosen = std::move(*candidates.by_plane[static_cast<std::size_t>(plane)]);
        chosen.passes.resize(static_cast<std::size_t>(kept));
        chosen.data.resize(chosen.passes.back().length);
      } else {
        coded.blocks[b].passes.clear();
      }
      for (int& v : plan) v = v > 0 ? kept : 0;
      candidates = HtCandidates{};
    });
    coded.ht_candidates.clear();
  }
}

const t1::EncodedBlock& ht_packet_plan(const CodedTile& coded, std::size_t block,
                                       std::span<const int> cumulative_passes, std::span<int> passes_out) {
  const int k = cumulative_passes.empty() ? 0 : cumulative_passes.back();
  const int kept = k > 0 ? coded.ht_candidates[block].point(k).passes : 0;
  for (std::size_t l = 0; l < cumulative_passes.size(); ++l) passes_out[l] = cumulative_passes[l] > 0 ? kept : 0;
  // Not included: a block with nothing (the truncation points' lengths are not of one codeword).
  static const t1::EncodedBlock nothing{};
  return k > 0 ? coded.ht_candidates[block].chosen(k) : nothing;
}

}  // namespace codec
