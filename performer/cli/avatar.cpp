#include "avatar.h"

#include <stdexcept>
#include <string>

#include "cli_character.h"
#include "performer/avatar.h"
#include "performer/body_mesh.h"
#include "performer/bvh.h"
#include "performer/gltf_skin.h"
#include "performer/procedural_head.h"
#include "performer/viseme_library.h"
#include "performer/viseme_set.h"

namespace performer::cli {

void run_avatar(const AvatarCommand& c, std::FILE* log) {
  const std::string extension = c.out.extension().string();
  if (extension != ".glb" && extension != ".gltf")
    throw std::invalid_argument("-o must be a .glb or .gltf file, not \"" + c.out.string() + "\"");
  const Bvh bvh = read_bvh(c.bvh);
  // glTF is in metres; the body knows the skeleton's metres per unit.
  const float metres = BodyMeshParams{}.meters_per_unit;
  const CliCharacter built = build_cli_character(
      bvh.skeleton, c.threads, build_procedural_head(load_viseme_set(default_viseme_dir() / "visemes.tsv")), metres);
  const AvatarExport avatar = character_avatar(built.character, bvh.skeleton);
  write_gltf_skinned(c.out, avatar.skin, avatar.targets);
  std::fprintf(log, "avatar: %zu vertices, %zu joints, %zu morph targets written to %s\n",
               avatar.skin.mesh.positions.size(), avatar.skin.joints.size(), avatar.targets.size(),
               c.out.string().c_str());
}

}  // namespace performer::cli
