// A program linked against the performer's MIT parts only (kinematics, visemes, mesh, head, face,
// body, character, glTF, render; tests/CMakeLists.txt), with every library on its link line kept
// as a dynamic dependency, for licence_boundary_test to inspect. It builds the generated performer
// (BVH, viseme set, procedural head, body, character) and reads a glTF avatar, so that those parts'
// objects are in it; all of the parts are on its link line. Built, not run by the tests.
#include <cstdio>
#include <vector>

#include "performer/bvh.h"
#include "performer/character.h"
#include "performer/gltf_avatar.h"
#include "performer/procedural_head.h"
#include "performer/viseme_library.h"

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s BVH [AVATAR.glb]\n", argv[0]);
    return 2;
  }
  const performer::VisemeLibrary library = performer::VisemeLibrary::load_default();
  const performer::Bvh bvh = performer::read_bvh(argv[1]);
  const performer::FaceModel head = performer::build_procedural_head(library.visemes());
  const performer::Character character = performer::build_character(bvh.skeleton, head);
  std::printf("%zu vertices, %zu face targets\n", character.mesh.positions.size(), character.targets.size());
  if (argc > 2) {
    const performer::GltfAvatar avatar = performer::load_gltf_avatar(argv[2], library.visemes());
    std::printf("avatar: %zu vertices\n", avatar.skin.mesh.positions.size());
  }
  return 0;
}
