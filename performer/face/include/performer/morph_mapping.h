// Which morph targets of an avatar make the performer's targets (thesis visemes, expressions,
// blink): the naming conventions of avatar rigs, kept as data (performer/data/morphs) so a new rig
// convention is a line in a file, not a code change.
//   oculus.tsv: Oculus viseme -> morph names that rigs give it (viseme_aa, viseme_I, ...)
//   arkit.tsv:  target -> weighted sum of ARKit blend shapes (blink = eyeBlinkLeft + eyeBlinkRight)
// See the files' headers for the formats.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace performer {

struct MorphIngredient {
  std::string morph;
  float weight = 1.0f;
};

struct MorphRecipe {
  std::string target;  // an expression name, "blink", or an Oculus viseme morph name (viseme_aa)
  std::vector<MorphIngredient> ingredients;
};

struct MorphMapping {
  struct OculusNames {
    std::string oculus;               // one of kOculusVisemes
    std::vector<std::string> morphs;  // names to try, in order
  };
  std::vector<OculusNames> oculus;
  std::vector<MorphRecipe> recipes;  // one per target, in file order

  // Morph names for an Oculus viseme (empty when none are listed).
  const std::vector<std::string>& oculus_morphs(std::string_view oculus_viseme) const;
  // The recipe for a target, or nullptr.
  const MorphRecipe* recipe(std::string_view target) const;
};

// performer_data_dir() / "morphs".
std::filesystem::path default_morph_dir();

// Throws VisemeDataError ("FILE:LINE: problem") for wrong field counts, unknown Oculus visemes,
// an Oculus viseme listed twice, weights that are not finite numbers, a recipe's lines not kept
// together, or a missing file.
MorphMapping parse_oculus_morphs(std::string_view text, std::string_view file_name, MorphMapping into = {});
MorphMapping parse_morph_recipes(std::string_view text, std::string_view file_name, MorphMapping into = {});
// Reads folder/oculus.tsv and folder/arkit.tsv.
MorphMapping load_morph_mapping(const std::filesystem::path& folder);

}  // namespace performer
