// Line-oriented reading shared by the lip-sync data readers (viseme tables, keyframes, Rhubarb TSV,
// expression keys, espeak-ng mappings, morph recipes). Not public API: shared by the visemes, speech
// and face parts. All of their files are "fields on a line, '#' comments", so line numbering,
// comment stripping and strict number parsing live here once.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace performer::detail {

struct TextLine {
  std::string_view text;  // without comment, line end or surrounding blanks; never empty
  int number = 0;         // 1-based
};

// Lines that hold anything besides blanks and comments. Accepts LF, CRLF and CR line ends and a
// UTF-8 byte order mark. The views point into `text`.
std::vector<TextLine> content_lines(std::string_view text, bool strip_comments = true);

// Fields separated by runs of tabs and spaces.
std::vector<std::string_view> split_fields(std::string_view line);

// A finite decimal number, the whole field (a leading '+' allowed); nullopt otherwise.
std::optional<double> parse_number(std::string_view field);

// A non-negative decimal integer, the whole field; nullopt otherwise.
std::optional<int> parse_index(std::string_view field);

// The whole file as text. Throws VisemeDataError(file, 0, "cannot open") when unreadable.
std::string read_text_file(const std::filesystem::path& file);

}  // namespace performer::detail
