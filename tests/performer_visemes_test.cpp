// Tests for the lip-sync data and timing sources: the viseme tables against the thesis itself
// (Tables 3.1-3.6 are parsed out of ../shared/seed/thesis.md, so a typo in a data file cannot hide
// behind a test that repeats it), the library and its errors, syllable splitting, manual keyframe
// files and Rhubarb Lip Sync output.

#include <gtest/gtest.h>

#include "support/scratch_dir.h"
#include "support/shared_assets.h"

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "performer/phoneme_keyframes.h"
#include "performer/syllable_parse.h"
#include "performer/syllable_split.h"
#include "performer/syllable_visemes.h"
#include "performer/viseme_error.h"
#include "performer/viseme_library.h"
#include "performer/viseme_rhubarb.h"
#include "performer/viseme_set.h"
#include "performer/viseme_table.h"

namespace fs = std::filesystem;
using performer::PhonemeRole;
using performer::TimedViseme;
using performer::VisemeDataError;
using performer::VisemeLibrary;

namespace {

// ---------------------------------------------------------------------------------------------
// The thesis' tables, read from the seed text.

struct ThesisRow {
  int phoneme_id;
  std::string symbol;
  int ipa_id;
  std::string ipa_symbol;
};

std::vector<std::string> split_tabs(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream in(line);
  std::string field;
  while (std::getline(in, field, '\t')) out.push_back(field);
  return out;
}

bool is_int(const std::string& s) { return !s.empty() && s.find_first_not_of("0123456789") == std::string::npos; }

// Every block under a "Phoneme ID / Phoneme Symbol / IPA ID / IPA Symbol" header, keyed by the
// number of the "Table 3.N:" caption that follows it (the markdown puts captions after the rows).
std::map<int, std::vector<ThesisRow>> thesis_tables(const fs::path& file) {
  std::ifstream in(file);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    lines.push_back(line);
  }
  std::map<int, std::vector<ThesisRow>> tables;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const auto header = split_tabs(lines[i]);
    if (header != std::vector<std::string>{"Phoneme ID", "Phoneme Symbol", "IPA ID", "IPA Symbol"}) continue;
    std::vector<ThesisRow> rows;
    std::size_t j = i + 1;
    for (; j < lines.size(); ++j) {
      const auto f = split_tabs(lines[j]);
      if (f.size() != 4 || !is_int(f[0]) || !is_int(f[2])) break;
      rows.push_back({std::stoi(f[0]), f[1], std::stoi(f[2]), f[3]});
    }
    while (j < lines.size() && lines[j].empty()) ++j;
    const std::string caption = "Table 3.";
    if (j < lines.size() && lines[j].rfind(caption, 0) == 0) {
      const int number = std::stoi(lines[j].substr(caption.size()));
      tables[number] = rows;
    }
  }
  return tables;
}

struct TableUse {
  int number;
  const char* language;
  PhonemeRole role;
  int first_phoneme_id;
  std::size_t rows;
};

// Which data file and role each thesis table is transcribed into. Row counts and first IDs are the
// tables' own (Tables 3.1-3.4 number their phonemes 0-38 in one run).
const TableUse kTableUses[] = {
    {1, "yue", PhonemeRole::onset, 0, 20}, {2, "yue", PhonemeRole::nucleus, 20, 9},
    {3, "yue", PhonemeRole::coda, 29, 8},  {4, "yue", PhonemeRole::nasal, 37, 2},
    {5, "ja", PhonemeRole::any, 0, 18},    {6, "cmn", PhonemeRole::any, 0, 31},
};

void PrintTo(const TableUse& u, std::ostream* os) {
  *os << "Table 3." << u.number << " (" << u.language << ", " << performer::role_name(u.role) << ")";
}

fs::path thesis_path() { return test_support::shared_dir() / "seed" / "thesis.md"; }

const VisemeLibrary& library() {
  static const VisemeLibrary lib = VisemeLibrary::load_default();
  return lib;
}

class ThesisTable : public ::testing::TestWithParam<TableUse> {};

TEST_P(ThesisTable, EveryEntryMapsToTheThesisVisemeId) {
  const TableUse& use = GetParam();
  const fs::path thesis = thesis_path();
  REQUIRE_SHARED_FILE(thesis);
  const auto tables = thesis_tables(thesis);
  ASSERT_TRUE(tables.count(use.number)) << "Table 3." << use.number << " not found in " << thesis;
  const auto& rows = tables.at(use.number);
  // The parser read the whole table: its phoneme IDs run on without a gap.
  ASSERT_EQ(rows.size(), use.rows) << "Table 3." << use.number;
  for (std::size_t r = 0; r < rows.size(); ++r)
    EXPECT_EQ(rows[r].phoneme_id, use.first_phoneme_id + static_cast<int>(r)) << "Table 3." << use.number;

  const performer::VisemeTable& table = library().table(use.language);
  for (const ThesisRow& row : rows) {
    SCOPED_TRACE("Table 3." + std::to_string(use.number) + " phoneme " + std::to_string(row.phoneme_id) + " '" +
                 row.symbol + "'");
    // The data file, through the library's answer.
    EXPECT_EQ(library().viseme_for(use.language, row.symbol, use.role), row.ipa_id);
    // The table's "IPA Symbol" column is the viseme's name in visemes.tsv.
    ASSERT_LT(row.ipa_id, library().viseme_count());
    EXPECT_EQ(library().visemes().visemes[static_cast<std::size_t>(row.ipa_id)].name, row.ipa_symbol);
    // And the file holds an entry of its own for it (not only a wildcard from elsewhere).
    bool listed = false;
    for (const auto& e : table.entries)
      if (e.symbol == row.symbol && (e.role == use.role || e.role == PhonemeRole::any || use.role == PhonemeRole::any))
        listed = listed || e.viseme == row.ipa_id;
    EXPECT_TRUE(listed) << "no entry in " << table.file;
  }
}

INSTANTIATE_TEST_SUITE_P(Tables3_1To3_6, ThesisTable, ::testing::ValuesIn(kTableUses),
                         [](const auto& info) { return "Table3_" + std::to_string(info.param.number); });

// The files hold the thesis' rows and, beyond them, only the additions their comments document.
TEST(ThesisTables, DataFilesAddOnlyDocumentedEntries) {
  const fs::path thesis = thesis_path();
  REQUIRE_SHARED_FILE(thesis);
  const auto tables = thesis_tables(thesis);
  const std::map<std::string, std::set<std::string>> additions = {
      {"yue", {"LP"}}, {"ja", {"z", "ts", "d", "sh", "ch", "j", "f"}}, {"cmn", {}}};
  for (const auto& [language, added] : additions) {
    std::set<std::string> thesis_symbols;
    for (const TableUse& use : kTableUses)
      if (use.language == language && tables.count(use.number))
        for (const ThesisRow& row : tables.at(use.number)) thesis_symbols.insert(row.symbol);
    std::set<std::string> extra;
    for (const auto& e : library().table(language).entries)
      if (!thesis_symbols.count(e.symbol)) extra.insert(e.symbol);
    EXPECT_EQ(extra, added) << language;
  }
  // Cantonese roles are the thesis' own: each role's entries are exactly its table's rows.
  for (const TableUse& use : kTableUses) {
    if (std::string(use.language) != "yue") continue;
    std::multiset<std::string> want, have;
    for (const ThesisRow& row : tables.at(use.number))
      if (row.symbol != "closed") want.insert(row.symbol);
    for (const auto& e : library().table("yue").entries)
      if (e.role == use.role) have.insert(e.symbol);
    EXPECT_EQ(have, want) << "Table 3." << use.number;
  }
}

// ---------------------------------------------------------------------------------------------
// Viseme set and library.

TEST(VisemeSet, IdsNamesAndOculusMapping) {
  const performer::VisemeSet& set = library().visemes();
  ASSERT_EQ(set.size(), 16) << "closed plus the thesis' 15 visemes";
  const char* names[] = {"closed", "IY", "EH", "AA", "O", "UH", "Y", "L", "M", "N", "NG", "F", "TH", "S", "SH", "K"};
  for (int i = 0; i < 16; ++i) {
    EXPECT_EQ(set.visemes[static_cast<std::size_t>(i)].id, i);
    EXPECT_EQ(set.visemes[static_cast<std::size_t>(i)].name, names[i]);
    EXPECT_EQ(set.find(names[i]), i);
  }
  EXPECT_EQ(set.visemes[0].oculus, "sil");
  EXPECT_EQ(set.visemes[8].oculus, "PP");
  EXPECT_EQ(set.visemes[3].oculus, "aa");
  EXPECT_EQ(set.find("nope"), -1);
}

TEST(VisemeLibrary, LoadsEveryLanguageOfTheFolder) {
  const auto langs = library().languages();
  for (const char* want : {"cmn", "en", "ja", "rhubarb", "yue"})
    EXPECT_NE(std::find(langs.begin(), langs.end(), want), langs.end()) << want;
  EXPECT_EQ(library().viseme_for("en", "TH"), 12);
  EXPECT_EQ(library().viseme_for("en", "ʃ"), 14);
  EXPECT_EQ(library().viseme_for("rhubarb", "A"), 8);
  EXPECT_EQ(library().viseme_for("yue", "u", PhonemeRole::coda), 5);
  EXPECT_EQ(library().viseme_for("yue", "u", PhonemeRole::nucleus), 4);
  EXPECT_EQ(library().viseme_for("yue", "ng"), 10) << "onset, coda and nasal agree";
}

TEST(VisemeLibrary, UnmappedSymbolsAndLanguagesAreNamed) {
  try {
    library().viseme_for("yue", "zz", PhonemeRole::onset);
    FAIL() << "expected UnmappedSymbolError";
  } catch (const performer::UnmappedSymbolError& e) {
    EXPECT_EQ(e.symbol(), "zz");
    EXPECT_EQ(e.language(), "yue");
    EXPECT_NE(std::string(e.what()).find("'zz'"), std::string::npos) << e.what();
  }
  // u is O as a nucleus and UH as a coda: asked without a role, it is ambiguous.
  try {
    library().viseme_for("yue", "u");
    FAIL() << "expected UnmappedSymbolError";
  } catch (const performer::UnmappedSymbolError& e) {
    EXPECT_NE(std::string(e.what()).find("give the role"), std::string::npos) << e.what();
  }
  // A nucleus-only symbol asked as a coda.
  EXPECT_THROW(library().viseme_for("yue", "aa", PhonemeRole::coda), performer::UnmappedSymbolError);
  try {
    library().viseme_for("xx", "a");
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("'xx'"), std::string::npos) << e.what();
  }
}

fs::path write_file(const fs::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

TEST(VisemeLibrary, AddingALanguageIsAddingAFile) {
  test_support::ScratchDir dir("performer_visemes");
  fs::copy_file(performer::default_viseme_dir() / "visemes.tsv", dir / "visemes.tsv");
  write_file(dir / "xx.tsv", "# toy language\nba onset b 8\no nucleus o 4\n");
  write_file(dir / "README.txt", "not a table\n");
  const VisemeLibrary lib = VisemeLibrary::load(dir.path());
  EXPECT_EQ(lib.languages(), std::vector<std::string>{"xx"});
  EXPECT_EQ(lib.viseme_for("xx", "ba", PhonemeRole::onset), 8);
}

TEST(VisemeLibrary, EnvironmentOverridesTheDataFolder) {
  const char* old = std::getenv("GPUJ2K_PERFORMER_DATA");
  const std::string saved = old ? old : "";
  ::setenv("GPUJ2K_PERFORMER_DATA", "/some/where", 1);
  EXPECT_EQ(performer::default_viseme_dir(), fs::path("/some/where") / "visemes");
  if (old)
    ::setenv("GPUJ2K_PERFORMER_DATA", saved.c_str(), 1);
  else
    ::unsetenv("GPUJ2K_PERFORMER_DATA");
  EXPECT_TRUE(fs::exists(performer::default_viseme_dir() / "visemes.tsv")) << performer::default_viseme_dir();
}

// A malformed table line is reported as FILE:LINE: problem.
void expect_table_error(const std::string& text, int line, const std::string& words) {
  try {
    performer::parse_viseme_table(text, "t.tsv", "t");
    FAIL() << "expected an error for:\n" << text;
  } catch (const VisemeDataError& e) {
    EXPECT_EQ(e.line(), line) << e.what();
    EXPECT_EQ(std::string(e.what()).rfind("t.tsv:" + std::to_string(line) + ": ", 0), 0u) << e.what();
    EXPECT_NE(e.problem().find(words), std::string::npos) << e.what();
  }
}

TEST(VisemeTable, MalformedLinesNameTheirLine) {
  expect_table_error("# c\na onset a 3\nb onset b\n", 3, "expected 4 fields");
  expect_table_error("a middle a 3\n", 1, "unknown role");
  expect_table_error("\n\na onset a -1\n", 3, "viseme ID");
  expect_table_error("a onset a x3\n", 1, "viseme ID");
  expect_table_error("a onset a 3\r\nb coda b 8\r\na onset a 4\r\n", 3, "already mapped on line 1");
}

TEST(VisemeTable, IdsOutsideTheSetAreCaughtWithTheirLine) {
  test_support::ScratchDir dir("performer_visemes");
  fs::copy_file(performer::default_viseme_dir() / "visemes.tsv", dir / "visemes.tsv");
  write_file(dir / "xx.tsv", "a any a 3\nb any b 16\n");
  try {
    VisemeLibrary::load(dir.path());
    FAIL() << "expected VisemeDataError";
  } catch (const VisemeDataError& e) {
    EXPECT_EQ(e.line(), 2) << e.what();
    EXPECT_NE(e.file().find("xx.tsv"), std::string::npos) << e.what();
  }
}

TEST(VisemeSet, MalformedLinesNameTheirLine) {
  EXPECT_THROW(performer::parse_viseme_set("0 closed sil\n2 IY ih\n", "v.tsv"), VisemeDataError);
  try {
    performer::parse_viseme_set("0 closed sil\n1 IY ee\n", "v.tsv");
    FAIL();
  } catch (const VisemeDataError& e) {
    EXPECT_EQ(e.line(), 2);
    EXPECT_NE(e.problem().find("Oculus"), std::string::npos);
  }
}

// ---------------------------------------------------------------------------------------------
// Syllables.

TEST(SyllableSplit, ThesisFractions) {
  // /zung/: 0.33 s; onset a quarter, nucleus and coda 0.375 each (thesis 3.4.3).
  const auto s = performer::split_syllable(1.0, 0.33, true, true);
  ASSERT_TRUE(s.onset && s.coda);
  EXPECT_DOUBLE_EQ(s.onset->start, 1.0);
  EXPECT_NEAR(s.onset->duration, 0.25 * 0.33, 1e-12);
  EXPECT_NEAR(s.nucleus.start, 1.0 + 0.25 * 0.33, 1e-12);
  EXPECT_NEAR(s.nucleus.duration, 0.375 * 0.33, 1e-12);
  EXPECT_NEAR(s.coda->start, 1.0 + 0.625 * 0.33, 1e-12);
  EXPECT_NEAR(s.coda->duration, 0.375 * 0.33, 1e-12);
  EXPECT_DOUBLE_EQ(s.coda->end(), 1.0 + 0.33) << "ends exactly at the syllable end";

  const auto no_coda = performer::split_syllable(0.0, 0.4, true, false);  // /nei/-like: n + ei... without coda
  EXPECT_FALSE(no_coda.coda);
  EXPECT_NEAR(no_coda.onset->duration, 0.1, 1e-12);
  EXPECT_NEAR(no_coda.nucleus.start, 0.1, 1e-12);
  EXPECT_NEAR(no_coda.nucleus.duration, 0.3, 1e-12);

  const auto no_onset = performer::split_syllable(2.0, 0.4, false, true);  // /am/
  EXPECT_FALSE(no_onset.onset);
  EXPECT_DOUBLE_EQ(no_onset.nucleus.start, 2.0) << "the nucleus starts at the syllable start";
  EXPECT_NEAR(no_onset.nucleus.duration, 0.2, 1e-12);
  EXPECT_NEAR(no_onset.coda->start, 2.2, 1e-12);
  EXPECT_NEAR(no_onset.coda->duration, 0.2, 1e-12);

  const auto bare = performer::split_syllable(0.5, 0.2, false, false);  // /aa/
  EXPECT_DOUBLE_EQ(bare.nucleus.start, 0.5);
  EXPECT_DOUBLE_EQ(bare.nucleus.duration, 0.2);

  EXPECT_THROW(performer::split_syllable(0.0, -0.1, true, true), std::invalid_argument);
  EXPECT_THROW(performer::split_syllable(0.0, 0.1, true, true, 1.0), std::invalid_argument);
}

std::string describe(const std::vector<performer::SyllablePhoneme>& parse) {
  std::string out;
  for (const auto& p : parse) out += (out.empty() ? "" : " ") + p.symbol + "/" + std::string(role_name(p.role));
  return out;
}

std::string parse_of(const char* language, const char* syllable) {
  const auto p = performer::parse_syllable(library().table(language), syllable);
  return p ? describe(*p) : "none";
}

TEST(SyllableParse, SplitsWithTheTableSymbols) {
  EXPECT_EQ(parse_of("yue", "zung1"), "z/onset u/nucleus ng/coda");
  EXPECT_EQ(parse_of("yue", "gan"), "g/onset a/nucleus n/coda");
  EXPECT_EQ(parse_of("yue", "nei5"), "n/onset e/nucleus i/coda");
  EXPECT_EQ(parse_of("yue", "lam4"), "l/onset a/nucleus m/coda");
  EXPECT_EQ(parse_of("yue", "gwaa"), "gw/onset aa/nucleus");
  EXPECT_EQ(parse_of("yue", "seoi3"), "s/onset eo/nucleus i/coda");
  EXPECT_EQ(parse_of("yue", "jyu"), "j/onset yu/nucleus");
  EXPECT_EQ(parse_of("yue", "m4"), "m/nasal");
  EXPECT_EQ(parse_of("yue", "ng5"), "ng/nasal");
  EXPECT_EQ(parse_of("yue", "aa"), "aa/nucleus");
  EXPECT_EQ(parse_of("cmn", "zhong1"), "zh/onset o/nucleus ng/coda");
  EXPECT_EQ(parse_of("cmn", "hao3"), "h/onset a/nucleus o/nucleus");
  EXPECT_EQ(parse_of("cmn", "er"), "e/nucleus r/coda");
  EXPECT_EQ(parse_of("ja", "ka"), "k/onset a/nucleus");
  EXPECT_EQ(parse_of("ja", "shi"), "sh/onset i/nucleus");
  EXPECT_EQ(parse_of("yue", "xq"), "none");
  EXPECT_EQ(parse_of("yue", "123"), "none");
}

TEST(SyllableVisemes, ZungGivesThreeTimedVisemes) {
  const auto v = performer::syllable_visemes(library().table("yue"), "zung1", 0.0, 0.33);
  ASSERT_EQ(v.size(), 3u);
  EXPECT_EQ(v[0].viseme, 13);  // z -> S
  EXPECT_EQ(v[1].viseme, 4);   // nucleus u -> O
  EXPECT_EQ(v[2].viseme, 10);  // coda ng -> NG
  EXPECT_NEAR(v[0].duration, 0.0825, 1e-12);
  EXPECT_NEAR(v[1].start, 0.0825, 1e-12);
  EXPECT_NEAR(v[1].duration, 0.12375, 1e-12);
  EXPECT_NEAR(v[2].start, 0.20625, 1e-12);
  EXPECT_NEAR(v[2].end(), 0.33, 1e-12);

  // Mandarin "hao": the two nucleus letters share the nucleus span.
  const auto hao = performer::syllable_visemes(library().table("cmn"), "hao", 0.0, 0.4);
  ASSERT_EQ(hao.size(), 3u);
  EXPECT_NEAR(hao[1].start, 0.1, 1e-12);
  EXPECT_NEAR(hao[1].duration, 0.15, 1e-12);
  EXPECT_NEAR(hao[2].start, 0.25, 1e-12);
  EXPECT_NEAR(hao[2].end(), 0.4, 1e-12);

  EXPECT_THROW(performer::syllable_visemes(library().table("yue"), "xq", 0.0, 0.3), performer::UnmappedSymbolError);
}

// ---------------------------------------------------------------------------------------------
// Manual keyframe files.

TEST(PhonemeKeyframes, ParsesPhonemesSyllablesAndRoles) {
  const std::string text =
      "# zung1 gan1, marked by hand\r\n"
      "0.00  0.33  zung1  yue\r\n"
      "\r\n"
      "0.33\t0.075\tg\tyue   # onset\r\n"
      "0.405 0.1125 a yue nucleus\r\n"
      "0.5175 0.1125 n yue coda\r\n"
      "0.63 0.2 LP yue\r\n"
      "+0.9 0.1 ka ja syllable\r\n";
  const auto keys = performer::parse_phoneme_keyframes(text, "k.txt");
  ASSERT_EQ(keys.size(), 6u);
  EXPECT_EQ(keys[0].line, 2);
  EXPECT_EQ(keys[1].line, 4);
  EXPECT_EQ(keys[1].symbol, "g");
  EXPECT_FALSE(keys[1].role);
  ASSERT_TRUE(keys[2].role);
  EXPECT_EQ(*keys[2].role, PhonemeRole::nucleus);
  EXPECT_TRUE(keys[5].syllable);
  EXPECT_DOUBLE_EQ(keys[5].start, 0.9);

  const auto v = performer::keyframes_to_visemes(keys, library(), "k.txt");
  const std::vector<int> ids = {13, 4, 10, 15, 3, 9, 0, 15, 3};
  ASSERT_EQ(v.size(), ids.size());
  for (std::size_t i = 0; i < ids.size(); ++i) EXPECT_EQ(v[i].viseme, ids[i]) << i;
  EXPECT_NEAR(v[2].end(), 0.33, 1e-12);
  EXPECT_NEAR(v[8].start, 0.925, 1e-12);
}

void expect_keyframe_error(const std::string& text, int line, const std::string& words) {
  try {
    const auto keys = performer::parse_phoneme_keyframes(text, "k.txt");
    performer::keyframes_to_visemes(keys, library(), "k.txt");
    FAIL() << "expected an error for:\n" << text;
  } catch (const VisemeDataError& e) {
    EXPECT_EQ(e.line(), line) << e.what();
    EXPECT_EQ(std::string(e.what()).rfind("k.txt:" + std::to_string(line) + ": ", 0), 0u) << e.what();
    EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
  }
}

TEST(PhonemeKeyframes, MalformedLinesNameTheirLine) {
  expect_keyframe_error("0 0.1 a yue\n0.1 0.2 a\n", 2, "expected 4 or 5 fields");
  expect_keyframe_error("# c\n\nx 0.1 a yue\n", 3, "start 'x' is not a number");
  expect_keyframe_error("0 0.1s a yue\n", 1, "duration '0.1s'");
  expect_keyframe_error("0 -0.1 a yue\n", 1, "negative");
  expect_keyframe_error("0 0.1 a yue vowel\n", 1, "unknown role 'vowel'");
  expect_keyframe_error("0 nan a yue\n", 1, "not a number");
  // Well-formed lines whose symbol or language the tables do not know.
  expect_keyframe_error("0 0.1 aa yue\n0.1 0.1 qx yue\n", 2, "'qx'");
  expect_keyframe_error("0 0.1 aa yue coda\n", 1, "'aa' as coda");
  expect_keyframe_error("0 0.1 a tlh\n", 1, "'tlh'");
}

TEST(PhonemeKeyframes, ReadsFiles) {
  test_support::ScratchDir dir("performer_visemes");
  const fs::path f = write_file(dir / "k.txt", "0 0.2 ni3 cmn\n0.2 0.3 hao3 cmn\n");
  const auto keys = performer::read_phoneme_keyframes(f);
  EXPECT_EQ(keys.size(), 2u);
  EXPECT_EQ(performer::keyframes_to_visemes(keys, library()).size(), 5u);
  try {
    performer::read_phoneme_keyframes(dir / "missing.txt");
    FAIL();
  } catch (const VisemeDataError& e) {
    EXPECT_EQ(e.line(), 0);
    EXPECT_NE(std::string(e.what()).find("cannot open"), std::string::npos);
  }
}

// ---------------------------------------------------------------------------------------------
// Rhubarb Lip Sync.

TEST(Rhubarb, ParsesTsv) {
  const auto cues = performer::parse_rhubarb_tsv("0.00\tX\n0.05\tD\n0.27\tC\n0.31\tB\n0.43\tX\n", "r.tsv");
  ASSERT_EQ(cues.size(), 5u);
  EXPECT_DOUBLE_EQ(cues[1].start, 0.05);
  EXPECT_DOUBLE_EQ(cues[1].end, 0.27) << "a cue lasts until the next";
  EXPECT_DOUBLE_EQ(cues[4].end, 0.43) << "the closing cue has no length";
  EXPECT_EQ(cues[3].line, 4);
  const auto v = performer::rhubarb_to_visemes(cues, library());
  ASSERT_EQ(v.size(), 5u);
  EXPECT_EQ(v[0].viseme, 0);   // X -> closed
  EXPECT_EQ(v[1].viseme, 3);   // D -> AA
  EXPECT_EQ(v[2].viseme, 2);   // C -> EH
  EXPECT_EQ(v[3].viseme, 13);  // B -> S
  EXPECT_NEAR(v[1].duration, 0.22, 1e-12);
}

TEST(Rhubarb, EveryShapeMaps) {
  const std::map<std::string, int> want = {{"A", 8}, {"B", 13}, {"C", 2}, {"D", 3}, {"E", 4},
                                           {"F", 5}, {"G", 11}, {"H", 7}, {"X", 0}};
  for (const auto& [shape, id] : want) EXPECT_EQ(library().viseme_for(performer::kRhubarbLanguage, shape), id) << shape;
}

void expect_rhubarb_error(bool json, const std::string& text, int line, const std::string& words) {
  try {
    if (json)
      performer::parse_rhubarb_json(text, "r");
    else
      performer::parse_rhubarb_tsv(text, "r");
    FAIL() << "expected an error for:\n" << text;
  } catch (const VisemeDataError& e) {
    EXPECT_EQ(e.line(), line) << e.what();
    EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
  }
}

TEST(Rhubarb, MalformedTsvNamesTheLine) {
  expect_rhubarb_error(false, "0.00\tX\n0.05\tQ\n", 2, "'Q' is not a Rhubarb shape");
  expect_rhubarb_error(false, "0.00\tX\n\nabc\tA\n", 3, "time 'abc'");
  expect_rhubarb_error(false, "0.00\tX\n0.50\tA\n0.40\tB\n", 3, "goes back");
  expect_rhubarb_error(false, "0.00\tX\tY\n", 1, "expected 2 fields");
}

const char* kRhubarbJson = R"({
  "metadata": {
    "soundFile": "C:\\speech\\hello \"world\".wav",
    "duration": 0.60,
    "tags": [1, 2.5e0, true, false, null, {"x": []}]
  },
  "mouthCues": [
    { "start": 0.00, "end": 0.05, "value": "X" },
    { "start": 0.05, "end": 0.27, "value": "D" },
    { "value": "F", "end": 0.60, "start": 0.27, "note": "\u00e9" }
  ]
}
)";

TEST(Rhubarb, ParsesJson) {
  const auto cues = performer::parse_rhubarb_json(kRhubarbJson, "r.json");
  ASSERT_EQ(cues.size(), 3u);
  EXPECT_EQ(cues[0].line, 8);
  EXPECT_DOUBLE_EQ(cues[1].end, 0.27);
  EXPECT_EQ(cues[2].shape, "F");
  EXPECT_DOUBLE_EQ(cues[2].start, 0.27);
  const auto v = performer::rhubarb_to_visemes(cues, library());
  EXPECT_EQ(v[2].viseme, 5);  // F -> UH
  EXPECT_NEAR(v[2].duration, 0.33, 1e-12);

  test_support::ScratchDir dir("performer_visemes");
  EXPECT_EQ(performer::read_rhubarb(write_file(dir / "a.json", kRhubarbJson)).size(), 3u);
  EXPECT_EQ(performer::read_rhubarb(write_file(dir / "a.txt", "0.00\tX\n0.10\tA\n")).size(), 2u);
}

TEST(Rhubarb, MalformedJsonNamesTheLine) {
  expect_rhubarb_error(true,
                       "{\"mouthCues\": [\n{\"start\": 0, \"end\": 1, \"value\": \"A\"},\n"
                       "{\"start\": 1, \"end\": 2, \"value\": \"Z\"}\n]}",
                       3, "'Z' is not a Rhubarb shape");
  expect_rhubarb_error(true, "{\"mouthCues\": [\n{\"start\": 0, \"end\": 1}\n]}", 2, "needs");
  expect_rhubarb_error(true, "{\"mouthCues\": [\n{\"start\": 0, \"end\": 1, \"value\": \"A\"},\n]}", 3, "a cue object");
  expect_rhubarb_error(true, "{\"mouthCues\": [\n{\"start\": 0,\n \"end\": 1x, \"value\": \"A\"}]}", 3, "expected");
  expect_rhubarb_error(true, "{\"mouthCues\": [\n{\"start\": 2, \"end\": 1, \"value\": \"A\"}]}", 2, "ends before");
  expect_rhubarb_error(true, "{\"metadata\": {}\n}", 0, "no \"mouthCues\"");
  expect_rhubarb_error(true, "[1, 2]", 1, "expected '{'");
  expect_rhubarb_error(true, "{\"mouthCues\": []}\n\nx", 3, "after the JSON");
  expect_rhubarb_error(true, "{\"mouthCues\": [{\"start\": 0, \"end\": 1, \"value\": \"A", 1, "unterminated");
  expect_rhubarb_error(true, std::string(200, '[') + std::string(200, ']'), 1, "expected '{'");
  expect_rhubarb_error(true, "{\"x\": " + std::string(200, '[') + std::string(200, ']') + ", \"mouthCues\": []}", 1,
                       "too deep");
}

}  // namespace
