#include "performer/viseme_library.h"

#include <algorithm>
#include <cstdlib>
#include <stdexcept>
#include <system_error>
#include <utility>

#include "performer/viseme_error.h"

#ifndef GPUJ2K_PERFORMER_DATA_DIR
#error "GPUJ2K_PERFORMER_DATA_DIR must name performer/data (performer/visemes/CMakeLists.txt sets it)"
#endif

namespace performer {

namespace {

constexpr std::string_view kSetFile = "visemes.tsv";

}  // namespace

std::filesystem::path performer_data_dir() {
  // The environment wins so an installed or relocated build can point at its data without a rebuild.
  if (const char* env = std::getenv("GPUJ2K_PERFORMER_DATA"); env && *env) return env;
  return GPUJ2K_PERFORMER_DATA_DIR;
}

std::filesystem::path default_viseme_dir() { return performer_data_dir() / "visemes"; }

VisemeLibrary VisemeLibrary::load(const std::filesystem::path& folder) {
  VisemeSet set = load_viseme_set(folder / kSetFile);
  std::vector<std::filesystem::path> files;
  std::error_code ec;
  for (std::filesystem::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec))
    if (it->is_regular_file() && it->path().extension() == ".tsv" && it->path().filename() != kSetFile)
      files.push_back(it->path());
  if (ec) throw VisemeDataError(folder.string(), 0, "cannot list: " + ec.message());
  // Directory order is the file system's; sorting makes languages() and error order reproducible.
  std::sort(files.begin(), files.end());
  std::vector<VisemeTable> tables;
  for (const auto& f : files) tables.push_back(load_viseme_table(f));
  return VisemeLibrary(std::move(set), std::move(tables));
}

VisemeLibrary::VisemeLibrary(VisemeSet set, std::vector<VisemeTable> tables)
    : set_(std::move(set)), tables_(std::move(tables)) {
  for (std::size_t i = 0; i < tables_.size(); ++i) {
    const VisemeTable& t = tables_[i];
    for (const VisemeEntry& e : t.entries)
      if (e.viseme >= set_.size())
        throw VisemeDataError(t.file, e.line,
                              "viseme ID " + std::to_string(e.viseme) + " is not in the viseme set (0-" +
                                  std::to_string(set_.size() - 1) + ")");
    for (std::size_t j = 0; j < i; ++j)
      if (tables_[j].language == t.language)
        throw VisemeDataError(t.file, 0, "language '" + t.language + "' already read from " + tables_[j].file);
  }
}

std::vector<std::string> VisemeLibrary::languages() const {
  std::vector<std::string> names;
  for (const VisemeTable& t : tables_) names.push_back(t.language);
  return names;
}

bool VisemeLibrary::has_language(std::string_view language) const {
  return std::any_of(tables_.begin(), tables_.end(), [&](const VisemeTable& t) { return t.language == language; });
}

const VisemeTable& VisemeLibrary::table(std::string_view language) const {
  for (const VisemeTable& t : tables_)
    if (t.language == language) return t;
  std::string have;
  for (const VisemeTable& t : tables_) have += (have.empty() ? "" : ", ") + t.language;
  throw std::invalid_argument("no viseme table for language '" + std::string(language) + "' (have: " + have + ")");
}

int VisemeLibrary::viseme_for(std::string_view language, std::string_view symbol, PhonemeRole role) const {
  return performer::viseme_for(table(language), symbol, role);
}

}  // namespace performer
