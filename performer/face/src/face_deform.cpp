#include "performer/face_deform.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include "base/thread_pool.h"

namespace performer {

namespace {

// A vec3 stream is a contiguous float stream three times as long; the sums below run over that
// flat view so the compiler sees one simple float loop per target it can vectorise, instead of a
// per-vertex loop over targets.
static_assert(sizeof(glm::vec3) == 3 * sizeof(float), "glm::vec3 must be three packed floats");

constexpr std::size_t kVerticesPerChunk = 4096;

const float* floats(std::span<const glm::vec3> s, std::size_t vertex) { return &s[vertex].x; }
float* floats(std::span<glm::vec3> s, std::size_t vertex) { return &s[vertex].x; }

// out[i] = base[i] + sum over targets of w_t dv_t[i], for the floats of vertices [begin, end).
// Targets are added one after another in target order: the same order for every chunk, so the
// threaded and serial results match bit for bit.
void blend_range(std::span<const glm::vec3> base, std::span<const std::span<const glm::vec3>> dvs,
                 std::span<const float> weights, std::span<glm::vec3> out, std::size_t begin, std::size_t end) {
  const std::size_t count = 3 * (end - begin);
  float* __restrict o = floats(out, begin);
  const float* __restrict b = floats(base, begin);
  for (std::size_t i = 0; i < count; ++i) o[i] = b[i];
  for (std::size_t t = 0; t < dvs.size(); ++t) {
    const float w = weights[t];
    // Weight 0 means "this DV is not acting" (3.4.1); skipping it keeps the neutral face exact and
    // makes cost proportional to the active DVs, as the shader's fixed 5 streams are.
    if (w == 0.0f) continue;
    const float* __restrict d = floats(dvs[t], begin);
    for (std::size_t i = 0; i < count; ++i) o[i] += w * d[i];
  }
}

void deform_range(const FaceDeformJob& job, std::size_t begin, std::size_t end) {
  blend_range(job.neutral_positions, job.position_dvs, job.weights, job.out_positions, begin, end);
  if (job.neutral_normals.empty()) return;
  // Equation 3.11 as printed sums the normal DVs without weights, which only makes sense when every
  // DV is fully on. The position sum 3.9 is weighted, and the normal DV is the first-order change of
  // the normal along the same path, so the same weights are applied here: weight 0 leaves the
  // neutral normal, weight 1 gives the target's normal (up to renormalisation), and a partial weight
  // interpolates between them like the positions do.
  blend_range(job.neutral_normals, job.normal_dvs, job.weights, job.out_normals, begin, end);
  // With no DV acting the neutral normals are the answer as stored; renormalising them would only
  // add rounding.
  bool acting = false;
  for (const float w : job.weights) acting = acting || w != 0.0f;
  if (!acting) return;
  for (std::size_t v = begin; v < end; ++v) {
    glm::vec3& n = job.out_normals[v];
    const float len = std::sqrt(n.x * n.x + n.y * n.y + n.z * n.z);
    // Opposite normals cancelling (a DV turning a normal by 180 degrees at half weight) leave no
    // direction; the neutral normal beats emitting NaN.
    n = len > 1e-12f ? n / len : job.neutral_normals[v];
  }
}

void check(const FaceDeformJob& job) {
  if (!job.valid())
    throw std::invalid_argument("deform_face: inconsistent job (stream sizes, target count or weight count disagree)");
}

}  // namespace

bool FaceDeformJob::valid() const {
  const std::size_t n = neutral_positions.size();
  const std::size_t targets = position_dvs.size();
  if (out_positions.size() != n || weights.size() != targets) return false;
  for (const auto& dv : position_dvs)
    if (dv.size() != n) return false;
  if (neutral_normals.empty()) return out_normals.empty();
  if (neutral_normals.size() != n || out_normals.size() != n || normal_dvs.size() != targets) return false;
  for (const auto& dv : normal_dvs)
    if (dv.size() != n) return false;
  return true;
}

void deform_face(const FaceDeformJob& job) {
  check(job);
  if (!job.neutral_positions.empty()) deform_range(job, 0, job.neutral_positions.size());
}

void deform_face_parallel(const FaceDeformJob& job, unsigned threads) {
  check(job);
  base::parallel_for(job.neutral_positions.size(), kVerticesPerChunk, threads,
                     [&job](std::size_t begin, std::size_t end) { deform_range(job, begin, end); });
}

FaceStreams::FaceStreams(const FaceModel& model) {
  positions.reserve(model.targets.size());
  normals.reserve(model.targets.size());
  for (const MorphTarget& t : model.targets) {
    positions.emplace_back(t.position_deltas);
    normals.emplace_back(t.normal_deltas);
  }
}

ChannelBinding bind_channels(std::span<const std::string> channels, const FaceModel& model) {
  ChannelBinding binding;
  binding.target_count = model.targets.size();
  binding.target_of_channel.reserve(channels.size());
  for (const std::string& name : channels) {
    const int t = model.find_target(name);
    binding.target_of_channel.push_back(t);
    if (t < 0) binding.unmatched.push_back(name);
  }
  return binding;
}

void target_weights(const ChannelBinding& binding, std::span<const float> frame, std::span<float> out) {
  if (frame.size() != binding.target_of_channel.size() || out.size() != binding.target_count)
    throw std::invalid_argument("target_weights: frame has " + std::to_string(frame.size()) + " channels for " +
                                std::to_string(binding.target_of_channel.size()) + " bound, output has " +
                                std::to_string(out.size()) + " for " + std::to_string(binding.target_count) +
                                " targets");
  for (float& w : out) w = 0.0f;
  for (std::size_t c = 0; c < frame.size(); ++c)
    if (const int t = binding.target_of_channel[c]; t >= 0) out[static_cast<std::size_t>(t)] = frame[c];
}

}  // namespace performer
