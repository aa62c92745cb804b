#include "performer/character_deform.h"

#include <algorithm>
#include <stdexcept>

#include "performer/face_deform.h"
#include "base/thread_pool.h"
#include "performer/skinning.h"

namespace performer {

namespace {

constexpr std::size_t kVerticesPerChunk = 4096;

void check(const CharacterDeformJob& job) {
  if (!job.valid())
    throw std::invalid_argument(
        "deform_character: inconsistent job (stream sizes, head range, target count or a joint index)");
}

// Step one, equations 3.9 and 3.11: the head range of the rest pose into the scratch streams.
FaceDeformJob face_job(const CharacterDeformJob& job) {
  FaceDeformJob face;
  face.neutral_positions = job.rest_positions.subspan(job.head_first, job.head_count);
  if (!job.rest_normals.empty()) face.neutral_normals = job.rest_normals.subspan(job.head_first, job.head_count);
  face.position_dvs = job.position_dvs;
  face.normal_dvs = job.normal_dvs;
  face.weights = job.face_weights;
  face.out_positions = job.head_positions;
  face.out_normals = job.head_normals;
  return face;
}

// Skins vertices [begin, end), all reading from one source: the rest streams for body vertices, the
// scratch streams (indexed from the head's first vertex) for head vertices.
void skin_piece(const CharacterDeformJob& job, std::size_t begin, std::size_t end, bool head) {
  if (begin >= end) return;
  const auto slots = static_cast<std::size_t>(job.influences);
  const std::size_t count = end - begin;
  SkinningJob s;
  s.influences = job.influences;
  s.matrices = job.matrices;
  s.joint_indices = job.joint_indices.subspan(begin * slots, count * slots);
  s.joint_weights = job.joint_weights.subspan(begin * slots, count * slots);
  const std::size_t source = head ? begin - job.head_first : begin;
  s.in_positions = (head ? std::span<const glm::vec3>(job.head_positions) : job.rest_positions).subspan(source, count);
  s.out_positions = job.out_positions.subspan(begin, count);
  if (!job.rest_normals.empty()) {
    s.in_normals = (head ? std::span<const glm::vec3>(job.head_normals) : job.rest_normals).subspan(source, count);
    s.out_normals = job.out_normals.subspan(begin, count);
  }
  skin(s);
}

// Step two, equations 3.17 and 3.19, for vertices [begin, end): split where the head range starts
// and ends so that each piece reads from one source.
void skin_range(const CharacterDeformJob& job, std::size_t begin, std::size_t end) {
  const std::size_t head_end = job.head_first + job.head_count;
  skin_piece(job, begin, std::min(end, job.head_first), false);
  skin_piece(job, std::max(begin, job.head_first), std::min(end, head_end), true);
  skin_piece(job, std::max(begin, head_end), end, false);
}

}  // namespace

bool CharacterDeformJob::valid() const {
  const std::size_t n = rest_positions.size();
  if (head_first > n || head_count > n - head_first) return false;
  if (influences < 1) return false;
  const std::size_t slots = n * static_cast<std::size_t>(influences);
  if (joint_indices.size() != slots || joint_weights.size() != slots) return false;
  if (out_positions.size() != n || head_positions.size() != head_count) return false;
  if (rest_normals.empty()) {
    if (!out_normals.empty() || !head_normals.empty()) return false;
  } else if (rest_normals.size() != n || out_normals.size() != n || head_normals.size() != head_count) {
    return false;
  }
  for (const std::uint16_t index : joint_indices)
    if (index >= matrices.size()) return false;
  return face_job(*this).valid();
}

void deform_character(const CharacterDeformJob& job) {
  check(job);
  deform_face(face_job(job));
  skin_range(job, 0, job.rest_positions.size());
}

void deform_character_parallel(const CharacterDeformJob& job, unsigned threads) {
  check(job);
  // The face step must finish before any head vertex is skinned; two passes keep that ordering
  // without per-chunk synchronisation. Both passes are per vertex, so chunking never changes a
  // result.
  deform_face_parallel(face_job(job), threads);
  base::parallel_for(job.rest_positions.size(), kVerticesPerChunk, threads,
                     [&job](std::size_t begin, std::size_t end) { skin_range(job, begin, end); });
}

CharacterFrame::CharacterFrame(const Character& character)
    : weights(character.targets.size(), 0.0f),
      matrices(character.inverse_bind.size(), glm::mat4(1.0f)),
      head_positions(character.head_count),
      head_normals(character.mesh.normals.empty() ? 0 : character.head_count),
      positions(character.vertex_count()),
      normals(character.mesh.normals.size()) {
  position_dvs.reserve(character.targets.size());
  normal_dvs.reserve(character.targets.size());
  for (const MorphTarget& t : character.targets) {
    position_dvs.emplace_back(t.position_deltas);
    normal_dvs.emplace_back(t.normal_deltas);
  }
}

CharacterDeformJob CharacterFrame::job(const Character& character) {
  CharacterDeformJob job;
  job.rest_positions = character.mesh.positions;
  job.rest_normals = character.mesh.normals;
  job.head_first = character.head_first;
  job.head_count = character.head_count;
  job.position_dvs = position_dvs;
  if (!character.mesh.normals.empty()) job.normal_dvs = normal_dvs;
  job.face_weights = weights;
  job.influences = character.influences;
  job.matrices = matrices;
  job.joint_indices = character.joint_indices;
  job.joint_weights = character.joint_weights;
  job.head_positions = head_positions;
  job.head_normals = head_normals;
  job.out_positions = positions;
  job.out_normals = normals;
  return job;
}

}  // namespace performer
