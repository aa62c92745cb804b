// Which visemes an espeak-ng phoneme shows, per voice: the bridge from espeak-ng's mnemonics to the
// thesis' viseme tables (data/visemes), kept as data (data/espeak/<voice>.tsv) so that a new voice
// or a better choice is a file edit. Entries name table symbols rather than bare IDs wherever the
// tables have the sound, so the thesis' tables stay the one place that says what a sound looks like.
//
// File format, one espeak-ng phoneme per line, fields separated by tabs or spaces:
//   mnemonic  language  symbol role [symbol role]...   entries of data/visemes/<language>.tsv
//   mnemonic  -         viseme-ID [viseme-ID]...        viseme IDs (visemes.tsv) where no symbol fits
// Several targets share the phoneme's time evenly, in order: espeak-ng speaks a Cantonese final
// such as "ei" as one phoneme, where the table has a nucleus e and a coda i. Roles are onset,
// nucleus, coda, nasal or any (viseme_table.h).
// A field that starts with '#' begins a comment running to the end of the line. Only at the start
// of a field, because mnemonics contain '#' ("t#", "a#"); the mnemonics that start with '#' are
// espeak-ng's internal virtual phonemes, which it never reports. Blank lines are ignored; LF, CRLF
// and a UTF-8 byte order mark are accepted.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "performer/viseme_library.h"

namespace performer {

struct EspeakVisemeEntry {
  std::string mnemonic;
  std::vector<int> visemes;  // one or more IDs, in spoken order
  int line = 0;              // where it was read, for error messages
};

struct EspeakVisemeMap {
  std::string voice;  // the file's stem: the espeak-ng voice (yue, cmn-latn-pinyin, ja, en-us)
  std::string file;   // as given to the loader, for error messages
  std::vector<EspeakVisemeEntry> entries;
};

// performer_data_dir() / "espeak".
std::filesystem::path default_espeak_viseme_dir();

// Parses a mapping, resolving every target through the library so that a bad line fails here, not
// in the middle of a performance. Throws VisemeDataError ("FILE:LINE: problem") for too few fields,
// a symbol without a role, an unknown role or language, a symbol the language's table lacks in
// that role, a viseme ID outside the set, or a mnemonic mapped twice.
EspeakVisemeMap parse_espeak_visemes(std::string_view text, std::string_view file_name, std::string voice,
                                     const VisemeLibrary& library);

// Reads a mapping file; the voice is the file name without its extension.
EspeakVisemeMap load_espeak_visemes(const std::filesystem::path& file, const VisemeLibrary& library);

// default_espeak_viseme_dir() / (voice + ".tsv").
EspeakVisemeMap load_default_espeak_visemes(std::string_view voice, const VisemeLibrary& library);

// The entry for a mnemonic; nullptr when the map has none.
const EspeakVisemeEntry* find_espeak_visemes(const EspeakVisemeMap& map, std::string_view mnemonic);

}  // namespace performer
