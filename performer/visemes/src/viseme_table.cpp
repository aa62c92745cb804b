#include "performer/viseme_table.h"

#include <utility>

#include "performer/viseme_error.h"
#include "performer/detail/viseme_text.h"

namespace performer {

VisemeTable parse_viseme_table(std::string_view text, std::string_view file_name, std::string language) {
  VisemeTable table{std::move(language), std::string(file_name), {}};
  const std::string file(file_name);
  for (const detail::TextLine& line : detail::content_lines(text)) {
    const auto fields = detail::split_fields(line.text);
    if (fields.size() != 4)
      throw VisemeDataError(file, line.number,
                            "expected 4 fields (symbol role IPA viseme-ID), found " + std::to_string(fields.size()));
    const auto role = parse_role(fields[1]);
    if (!role)
      throw VisemeDataError(file, line.number,
                            "unknown role '" + std::string(fields[1]) + "' (onset, nucleus, coda, nasal or any)");
    const auto viseme = detail::parse_index(fields[3]);
    if (!viseme)
      throw VisemeDataError(file, line.number,
                            "viseme ID '" + std::string(fields[3]) + "' is not a non-negative integer");
    // A repeated key would make the lookup depend on line order, which nobody editing a table
    // expects; say where the first one is.
    for (const VisemeEntry& e : table.entries)
      if (e.symbol == fields[0] && e.role == *role)
        throw VisemeDataError(file, line.number,
                              "'" + std::string(fields[0]) + "' as " + std::string(role_name(*role)) +
                                  " already mapped on line " + std::to_string(e.line));
    table.entries.push_back({std::string(fields[0]), *role, std::string(fields[2]), *viseme, line.number});
  }
  return table;
}

VisemeTable load_viseme_table(const std::filesystem::path& file) {
  return parse_viseme_table(detail::read_text_file(file), file.string(), file.stem().string());
}

std::optional<int> find_viseme(const VisemeTable& table, std::string_view symbol, PhonemeRole role) {
  if (role == PhonemeRole::any) {
    std::optional<int> found;
    for (const VisemeEntry& e : table.entries) {
      if (e.symbol != symbol) continue;
      if (found && *found != e.viseme) return std::nullopt;  // the roles disagree: the caller must pick
      found = e.viseme;
    }
    return found;
  }
  std::optional<int> wildcard;
  for (const VisemeEntry& e : table.entries) {
    if (e.symbol != symbol) continue;
    if (e.role == role) return e.viseme;
    if (e.role == PhonemeRole::any) wildcard = e.viseme;
  }
  return wildcard;
}

bool fits_role(const VisemeTable& table, std::string_view symbol, PhonemeRole role) {
  for (const VisemeEntry& e : table.entries)
    if (e.symbol == symbol && (e.role == role || e.role == PhonemeRole::any)) return true;
  return false;
}

int viseme_for(const VisemeTable& table, std::string_view symbol, PhonemeRole role) {
  if (const auto v = find_viseme(table, symbol, role)) return *v;
  bool present = false;
  for (const VisemeEntry& e : table.entries) present = present || e.symbol == symbol;
  std::string detail;
  if (role == PhonemeRole::any && present)
    detail = "its roles map to different visemes; give the role";
  else if (present)
    detail = "the table has it only in other roles";
  else
    detail = "not in " + table.file;
  throw UnmappedSymbolError(table.language, std::string(symbol), role, detail);
}

}  // namespace performer
