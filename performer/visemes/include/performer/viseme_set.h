// The viseme set itself (thesis Figure 3.5): the IDs and names the language tables point at, one
// face model (deformation vector) each, and the Oculus viseme each corresponds to. Read from
// performer/data/visemes/visemes.tsv:
//   ID  name  oculus
// one line per viseme, IDs 0, 1, 2, ... in order, '#' comments.
#pragma once

#include <array>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace performer {

// The 15 Oculus (Meta) Lipsync visemes, in Oculus' order: the de facto names of viseme morph
// targets in avatar models.
inline constexpr std::array<std::string_view, 15> kOculusVisemes = {"sil", "PP", "FF", "TH", "DD", "kk", "CH", "SS",
                                                                    "nn",  "RR", "aa", "E",  "ih", "oh", "ou"};

struct VisemeInfo {
  int id = 0;
  std::string name;    // the thesis' "IPA Symbol": closed, IY, EH, AA, ...
  std::string oculus;  // one of kOculusVisemes
};

struct VisemeSet {
  std::vector<VisemeInfo> visemes;  // visemes[i].id == i
  int size() const { return static_cast<int>(visemes.size()); }
  // The ID with this name; -1 when there is none.
  int find(std::string_view name) const;
};

// Throws VisemeDataError on wrong field counts, IDs out of order, repeated names, Oculus names not in
// kOculusVisemes, or an empty set.
VisemeSet parse_viseme_set(std::string_view text, std::string_view file_name);
VisemeSet load_viseme_set(const std::filesystem::path& file);

}  // namespace performer
