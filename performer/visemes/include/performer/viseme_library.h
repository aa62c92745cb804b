// Every language table of a data folder, checked against the viseme set: the one place callers ask
// "which viseme is this phoneme". The folder holds visemes.tsv (the set) and one <language>.tsv per
// language; dropping in a new file adds a language.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "performer/phoneme_role.h"
#include "performer/viseme_set.h"
#include "performer/viseme_table.h"

namespace performer {

// The performer's data folder: $GPUJ2K_PERFORMER_DATA when set and non-empty, else the source tree's
// performer/data (compiled in, so tests and uninstalled builds find it without setup).
std::filesystem::path performer_data_dir();

// performer_data_dir() / "visemes".
std::filesystem::path default_viseme_dir();

class VisemeLibrary {
 public:
  // Reads folder/visemes.tsv and every other *.tsv in the folder (in name order). Throws
  // VisemeDataError for a missing or malformed file, or a table naming a viseme ID the set lacks.
  static VisemeLibrary load(const std::filesystem::path& folder);
  static VisemeLibrary load_default() { return load(default_viseme_dir()); }

  // Checks every table's viseme IDs against the set (VisemeDataError naming file and line), and
  // that no two tables share a language.
  VisemeLibrary(VisemeSet set, std::vector<VisemeTable> tables);

  const VisemeSet& visemes() const { return set_; }
  int viseme_count() const { return set_.size(); }
  std::vector<std::string> languages() const;
  bool has_language(std::string_view language) const;
  // Throws std::invalid_argument naming the languages there are.
  const VisemeTable& table(std::string_view language) const;

  // The viseme of a symbol in a role (see find_viseme). Throws UnmappedSymbolError naming language,
  // symbol and role; std::invalid_argument for an unknown language.
  int viseme_for(std::string_view language, std::string_view symbol, PhonemeRole role = PhonemeRole::any) const;

 private:
  VisemeSet set_;
  std::vector<VisemeTable> tables_;
};

}  // namespace performer
