// One language's phoneme -> viseme table (thesis 3.4.2, Tables 3.1-3.6): the data that makes the
// lip sync multilingual. Adding a language is adding a file; nothing here knows any language.
//
// File format (performer/data/visemes/*.tsv): one entry per line,
//   symbol  role  IPA  viseme-ID
// separated by tabs or spaces; '#' starts a comment (to the end of the line); blank lines are
// ignored; LF, CRLF and a UTF-8 byte order mark are accepted. role is onset, nucleus, coda, nasal or
// any; IPA is a reference transcription ("-" for none); viseme-ID indexes visemes.tsv.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "performer/phoneme_role.h"

namespace performer {

struct VisemeEntry {
  std::string symbol;
  PhonemeRole role = PhonemeRole::any;
  std::string ipa;
  int viseme = 0;
  int line = 0;  // where it was read, for error messages
};

struct VisemeTable {
  std::string language;  // the file's stem: yue, ja, cmn, en, ...
  std::string file;      // as given to the loader, for error messages
  std::vector<VisemeEntry> entries;
};

// Parses table text. Throws VisemeDataError ("FILE:LINE: problem") on a wrong field count, an
// unknown role, a viseme ID that is not a non-negative integer, or a repeated (symbol, role) pair.
// Whether the IDs exist in the viseme set is checked by VisemeLibrary, which knows the set.
VisemeTable parse_viseme_table(std::string_view text, std::string_view file_name, std::string language);

// Reads a table file; the language is the file name without its extension.
VisemeTable load_viseme_table(const std::filesystem::path& file);

// The viseme for a symbol in a role: the entry with exactly that role, else an entry of role any.
// Asked with role any, every entry of the symbol must agree on the viseme; nullopt when they do not,
// or when the symbol is absent.
std::optional<int> find_viseme(const VisemeTable& table, std::string_view symbol, PhonemeRole role);

// Whether the symbol may stand in the role (an entry with that role or with role any).
bool fits_role(const VisemeTable& table, std::string_view symbol, PhonemeRole role);

// find_viseme that throws UnmappedSymbolError instead of returning nullopt.
int viseme_for(const VisemeTable& table, std::string_view symbol, PhonemeRole role);

}  // namespace performer
