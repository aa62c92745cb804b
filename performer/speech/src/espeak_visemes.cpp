#include "performer/espeak_visemes.h"

#include <algorithm>
#include <span>
#include <utility>

#include "performer/phoneme_role.h"
#include "performer/viseme_error.h"
#include "performer/viseme_table.h"
#include "performer/detail/viseme_text.h"

namespace performer {

namespace {

constexpr std::string_view kDirectIds = "-";

// A line's fields up to the first one that starts a comment.
std::vector<std::string_view> fields_before_comment(std::string_view line) {
  std::vector<std::string_view> fields = detail::split_fields(line);
  const auto comment =
      std::find_if(fields.begin(), fields.end(), [](std::string_view f) { return f.starts_with('#'); });
  fields.erase(comment, fields.end());
  return fields;
}

// "mnemonic - ID..." targets: viseme IDs in the set.
std::vector<int> direct_visemes(std::span<const std::string_view> ids, const VisemeLibrary& library,
                                const std::string& file, int line) {
  std::vector<int> visemes;
  for (std::string_view field : ids) {
    const auto id = detail::parse_index(field);
    if (!id || *id >= library.viseme_count())
      throw VisemeDataError(file, line,
                            "viseme ID '" + std::string(field) + "' is not in the viseme set (0-" +
                                std::to_string(library.viseme_count() - 1) + ")");
    visemes.push_back(*id);
  }
  return visemes;
}

int table_viseme(const VisemeTable& table, std::string_view symbol, std::string_view role_field,
                 const std::string& file, int line) {
  const auto role = parse_role(role_field);
  if (!role)
    throw VisemeDataError(file, line,
                          "unknown role '" + std::string(role_field) + "' (onset, nucleus, coda, nasal or any)");
  if (const auto viseme = find_viseme(table, symbol, *role)) return *viseme;
  throw VisemeDataError(file, line,
                        "'" + std::string(symbol) + "' as " + std::string(role_name(*role)) + " is not mapped by " +
                            table.file + (*role == PhonemeRole::any ? " (or its roles disagree; give one)" : ""));
}

// "mnemonic language symbol role..." targets: visemes of entries in the language's table.
std::vector<int> table_visemes(std::string_view language, std::span<const std::string_view> pairs,
                               const VisemeLibrary& library, const std::string& file, int line) {
  if (!library.has_language(language)) {
    std::string have;
    for (const std::string& l : library.languages()) have += (have.empty() ? "" : ", ") + l;
    throw VisemeDataError(file, line,
                          "no viseme table for language '" + std::string(language) + "' (have: " + have + ")");
  }
  if (pairs.size() % 2 != 0)
    throw VisemeDataError(file, line, "symbol '" + std::string(pairs.back()) + "' has no role");
  const VisemeTable& table = library.table(language);
  std::vector<int> visemes;
  for (std::size_t i = 0; i < pairs.size(); i += 2)
    visemes.push_back(table_viseme(table, pairs[i], pairs[i + 1], file, line));
  return visemes;
}

}  // namespace

std::filesystem::path default_espeak_viseme_dir() { return performer_data_dir() / "espeak"; }

EspeakVisemeMap parse_espeak_visemes(std::string_view text, std::string_view file_name, std::string voice,
                                     const VisemeLibrary& library) {
  EspeakVisemeMap map{std::move(voice), std::string(file_name), {}};
  const std::string& file = map.file;
  // Comments are found per field (fields_before_comment), not by content_lines: '#' is part of
  // some mnemonics.
  for (const detail::TextLine& line : detail::content_lines(text, /*strip_comments=*/false)) {
    const auto fields = fields_before_comment(line.text);
    if (fields.empty()) continue;
    if (fields.size() < 3)
      throw VisemeDataError(file, line.number,
                            "expected 'mnemonic language symbol role...' or 'mnemonic - viseme-ID...', found " +
                                std::to_string(fields.size()) + " field(s)");
    const std::string_view mnemonic = fields[0];
    if (const EspeakVisemeEntry* earlier = find_espeak_visemes(map, mnemonic))
      throw VisemeDataError(file, line.number,
                            "'" + std::string(mnemonic) + "' already mapped on line " + std::to_string(earlier->line));
    const std::span<const std::string_view> targets(fields.begin() + 2, fields.end());
    std::vector<int> visemes = fields[1] == kDirectIds ? direct_visemes(targets, library, file, line.number)
                                                       : table_visemes(fields[1], targets, library, file, line.number);
    map.entries.push_back({std::string(mnemonic), std::move(visemes), line.number});
  }
  return map;
}

EspeakVisemeMap load_espeak_visemes(const std::filesystem::path& file, const VisemeLibrary& library) {
  return parse_espeak_visemes(detail::read_text_file(file), file.string(), file.stem().string(), library);
}

EspeakVisemeMap load_default_espeak_visemes(std::string_view voice, const VisemeLibrary& library) {
  return load_espeak_visemes(default_espeak_viseme_dir() / (std::string(voice) + ".tsv"), library);
}

const EspeakVisemeEntry* find_espeak_visemes(const EspeakVisemeMap& map, std::string_view mnemonic) {
  for (const EspeakVisemeEntry& e : map.entries)
    if (e.mnemonic == mnemonic) return &e;
  return nullptr;
}

}  // namespace performer
