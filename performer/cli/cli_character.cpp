#include "cli_character.h"

#include <stdexcept>
#include <string>
#include <utility>

#include "performer/procedural_head.h"
#include "performer/viseme_library.h"
#include "performer/viseme_set.h"

namespace performer::cli {

void check_frame_range(const Bvh& bvh, const std::filesystem::path& file, int first, int last) {
  const int frames = bvh.motion.frames;
  if (frames == 0 || first < 0 || last >= frames || first > last)
    throw std::invalid_argument("frames " + std::to_string(first) + ".." + std::to_string(last) + " outside " +
                                file.string() + "'s " +
                                (frames > 0 ? "0.." + std::to_string(frames - 1) : std::string("(no frames)")));
}

CliCharacter build_cli_character(const Skeleton& skeleton, unsigned threads) {
  return build_cli_character(skeleton, threads,
                             build_procedural_head(load_viseme_set(default_viseme_dir() / "visemes.tsv")));
}

CliCharacter build_cli_character(const Skeleton& skeleton, unsigned threads, FaceModel face, float output_scale) {
  CliCharacter out;
  out.face = std::move(face);
  CharacterParams params;
  params.threads = threads;
  params.body.threads = threads;
  params.body.output_scale = output_scale;
  out.character = build_character(skeleton, out.face, params);
  return out;
}

}  // namespace performer::cli
