#include "performer/viseme_rhubarb.h"

#include "performer/viseme_error.h"
#include "performer/detail/viseme_text.h"

namespace performer {

bool is_rhubarb_shape(std::string_view shape) {
  return shape.size() == 1 && std::string_view("ABCDEFGHX").find(shape[0]) != std::string_view::npos;
}

std::vector<MouthCue> parse_rhubarb_tsv(std::string_view text, std::string_view file_name) {
  const std::string file(file_name);
  std::vector<MouthCue> cues;
  // Rhubarb writes no comments; '#' is left to fail as a bad time rather than hide data.
  for (const detail::TextLine& line : detail::content_lines(text, false)) {
    const auto fields = detail::split_fields(line.text);
    if (fields.size() != 2)
      throw VisemeDataError(file, line.number,
                            "expected 2 fields (time shape), found " + std::to_string(fields.size()));
    const auto time = detail::parse_number(fields[0]);
    if (!time) throw VisemeDataError(file, line.number, "time '" + std::string(fields[0]) + "' is not a number");
    if (!is_rhubarb_shape(fields[1]))
      throw VisemeDataError(file, line.number, "'" + std::string(fields[1]) + "' is not a Rhubarb shape (A-H, X)");
    if (!cues.empty() && *time < cues.back().start)
      throw VisemeDataError(file, line.number,
                            "time goes back (previous cue at " + std::to_string(cues.back().start) + ")");
    // A cue lasts until the next begins.
    if (!cues.empty()) cues.back().end = *time;
    cues.push_back({*time, *time, std::string(fields[1]), line.number});
  }
  return cues;
}

std::vector<MouthCue> read_rhubarb(const std::filesystem::path& file) {
  const std::string text = detail::read_text_file(file);
  const auto first = text.find_first_not_of(" \t\r\n\xEF\xBB\xBF");
  if (first != std::string::npos && text[first] == '{') return parse_rhubarb_json(text, file.string());
  return parse_rhubarb_tsv(text, file.string());
}

std::vector<TimedViseme> rhubarb_to_visemes(std::span<const MouthCue> cues, const VisemeLibrary& library) {
  std::vector<TimedViseme> out;
  out.reserve(cues.size());
  for (const MouthCue& c : cues)
    out.push_back({c.start, c.end - c.start, library.viseme_for(kRhubarbLanguage, c.shape, PhonemeRole::any)});
  return out;
}

}  // namespace performer
