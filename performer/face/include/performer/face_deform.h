// Facial deformation, per-frame step (thesis 3.4.4-3.4.5): the neutral face plus weighted
// deformation vectors, equation 3.9 (3.6 and 3.10 are the same sum), and the normals by equation
// 3.11. The data is laid out as the thesis' vertex shader consumes it: the neutral streams, one
// position and one normal DV stream per target, and one weight per target shared by all vertices
// (the shader's constants).
#pragma once

#include <cstddef>
#include <span>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "performer/face_model.h"
#include "performer/weights_track.h"

namespace performer {

// One deformation pass: plain views of the streams, owning nothing.
struct FaceDeformJob {
  std::span<const glm::vec3> neutral_positions;
  std::span<const glm::vec3> neutral_normals;                // empty to skip normals
  std::span<const std::span<const glm::vec3>> position_dvs;  // one stream per target
  std::span<const std::span<const glm::vec3>> normal_dvs;    // same count, or empty when skipping normals
  std::span<const float> weights;                            // one per target: alpha_i and beta_j of 3.9
  std::span<glm::vec3> out_positions;                        // must not overlap any input
  std::span<glm::vec3> out_normals;                          // empty exactly when neutral_normals is

  // Stream sizes agree and outputs are present as described above. Cost: one pass over the targets.
  bool valid() const;
};

// Equation 3.9: out_p = p_neutral + sum_i w_i DV_i. Equation 3.11 with weights:
// out_n = normalize(n_neutral + sum_i w_i DVn_i). Targets with weight exactly 0 are skipped, so all
// weights 0 reproduce the neutral mesh bit for bit. Throws std::invalid_argument when !job.valid().
void deform_face(const FaceDeformJob& job);

// deform_face() over vertex chunks on up to `threads` threads (0: hardware concurrency). Identical
// output: each vertex sums its targets in the same order whichever thread runs it.
void deform_face_parallel(const FaceDeformJob& job, unsigned threads = 0);

// The DV streams of a model, in target order, for building a FaceDeformJob:
//   FaceStreams s(model);
//   FaceDeformJob job{model.positions, model.normals, s.positions, s.normals, weights, out_p, out_n};
struct FaceStreams {
  std::vector<std::span<const glm::vec3>> positions;
  std::vector<std::span<const glm::vec3>> normals;
  explicit FaceStreams(const FaceModel& model);
};

// Which target each weight channel drives, matched by name: a WeightTrack's channels (viseme names,
// expression names, "blink") onto a FaceModel's targets. Channels with no target of that name are
// ignored when weights are applied, as the thesis' shader simply has no stream for them, and listed
// in `unmatched` so a caller can warn (a face with no "worry" target cannot worry).
struct ChannelBinding {
  std::vector<int> target_of_channel;  // per channel: index into FaceModel::targets, or -1
  std::vector<std::string> unmatched;  // names of the channels with -1, in channel order
  std::size_t target_count = 0;
};
ChannelBinding bind_channels(std::span<const std::string> channels, const FaceModel& model);
inline ChannelBinding bind_channels(const WeightTrack& track, const FaceModel& model) {
  return bind_channels(track.channels, model);
}

// out[t] = the weight of the channel bound to target t (0 for targets no channel drives): one
// WeightTrack frame (track.frame(f)) as the weights of a FaceDeformJob.
// Throws std::invalid_argument when frame.size() differs from the channel count or out.size() from
// the target count.
void target_weights(const ChannelBinding& binding, std::span<const float> frame, std::span<float> out);

}  // namespace performer
