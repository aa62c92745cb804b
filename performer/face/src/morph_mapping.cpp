#include "performer/morph_mapping.h"

#include <algorithm>
#include <cmath>

#include "performer/viseme_error.h"
#include "performer/viseme_library.h"
#include "performer/viseme_set.h"
#include "performer/detail/viseme_text.h"

namespace performer {

const std::vector<std::string>& MorphMapping::oculus_morphs(std::string_view oculus_viseme) const {
  static const std::vector<std::string> none;
  for (const OculusNames& o : oculus)
    if (o.oculus == oculus_viseme) return o.morphs;
  return none;
}

const MorphRecipe* MorphMapping::recipe(std::string_view target) const {
  for (const MorphRecipe& r : recipes)
    if (r.target == target) return &r;
  return nullptr;
}

std::filesystem::path default_morph_dir() { return performer_data_dir() / "morphs"; }

MorphMapping parse_oculus_morphs(std::string_view text, std::string_view file_name, MorphMapping into) {
  const std::string file(file_name);
  for (const detail::TextLine& line : detail::content_lines(text)) {
    const auto fields = detail::split_fields(line.text);
    if (fields.size() < 2)
      throw VisemeDataError(file, line.number, "expected an Oculus viseme and at least one morph name");
    if (std::find(kOculusVisemes.begin(), kOculusVisemes.end(), fields[0]) == kOculusVisemes.end())
      throw VisemeDataError(file, line.number, "'" + std::string(fields[0]) + "' is not an Oculus viseme");
    if (!into.oculus_morphs(fields[0]).empty())
      throw VisemeDataError(file, line.number, "Oculus viseme '" + std::string(fields[0]) + "' listed twice");
    MorphMapping::OculusNames names{std::string(fields[0]), {}};
    for (std::size_t i = 1; i < fields.size(); ++i) names.morphs.emplace_back(fields[i]);
    into.oculus.push_back(std::move(names));
  }
  return into;
}

MorphMapping parse_morph_recipes(std::string_view text, std::string_view file_name, MorphMapping into) {
  const std::string file(file_name);
  for (const detail::TextLine& line : detail::content_lines(text)) {
    const auto fields = detail::split_fields(line.text);
    if (fields.size() != 3)
      throw VisemeDataError(file, line.number,
                            "expected 3 fields (target weight morph), found " + std::to_string(fields.size()));
    const auto weight = detail::parse_number(fields[1]);
    if (!weight) throw VisemeDataError(file, line.number, "weight '" + std::string(fields[1]) + "' is not a number");
    const std::string target(fields[0]);
    // Lines of one recipe are kept together so the file reads as a list of recipes.
    if (into.recipes.empty() || into.recipes.back().target != target) {
      if (into.recipe(target))
        throw VisemeDataError(file, line.number, "recipe for '" + target + "' continues after other recipes");
      into.recipes.push_back({target, {}});
    }
    into.recipes.back().ingredients.push_back({std::string(fields[2]), static_cast<float>(*weight)});
  }
  return into;
}

MorphMapping load_morph_mapping(const std::filesystem::path& folder) {
  const auto oculus = folder / "oculus.tsv", arkit = folder / "arkit.tsv";
  MorphMapping m = parse_oculus_morphs(detail::read_text_file(oculus), oculus.string());
  return parse_morph_recipes(detail::read_text_file(arkit), arkit.string(), std::move(m));
}

}  // namespace performer
