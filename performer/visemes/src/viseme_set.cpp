#include "performer/viseme_set.h"

#include <algorithm>

#include "performer/viseme_error.h"
#include "performer/detail/viseme_text.h"

namespace performer {

int VisemeSet::find(std::string_view name) const {
  for (const VisemeInfo& v : visemes)
    if (v.name == name) return v.id;
  return -1;
}

VisemeSet parse_viseme_set(std::string_view text, std::string_view file_name) {
  const std::string file(file_name);
  VisemeSet set;
  for (const detail::TextLine& line : detail::content_lines(text)) {
    const auto fields = detail::split_fields(line.text);
    if (fields.size() != 3)
      throw VisemeDataError(file, line.number,
                            "expected 3 fields (ID name oculus), found " + std::to_string(fields.size()));
    const auto id = detail::parse_index(fields[0]);
    // Weight columns are indexed by ID, so the IDs must be exactly the positions.
    if (!id || *id != set.size())
      throw VisemeDataError(file, line.number,
                            "viseme ID '" + std::string(fields[0]) + "' should be " + std::to_string(set.size()) +
                                " (IDs run 0, 1, 2, ... in order)");
    if (set.find(fields[1]) >= 0)
      throw VisemeDataError(file, line.number, "viseme name '" + std::string(fields[1]) + "' repeated");
    if (std::find(kOculusVisemes.begin(), kOculusVisemes.end(), fields[2]) == kOculusVisemes.end())
      throw VisemeDataError(file, line.number,
                            "'" + std::string(fields[2]) +
                                "' is not an Oculus viseme (sil PP FF TH DD kk CH SS nn RR aa "
                                "E ih oh ou)");
    set.visemes.push_back({*id, std::string(fields[1]), std::string(fields[2])});
  }
  if (set.visemes.empty()) throw VisemeDataError(file, 0, "no visemes");
  return set;
}

VisemeSet load_viseme_set(const std::filesystem::path& file) {
  return parse_viseme_set(detail::read_text_file(file), file.string());
}

}  // namespace performer
