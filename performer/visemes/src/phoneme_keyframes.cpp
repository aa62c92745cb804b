#include "performer/phoneme_keyframes.h"

#include <algorithm>
#include <stdexcept>

#include "performer/syllable_visemes.h"
#include "performer/viseme_error.h"
#include "performer/detail/viseme_text.h"

namespace performer {

std::vector<PhonemeKeyframe> parse_phoneme_keyframes(std::string_view text, std::string_view file_name) {
  const std::string file(file_name);
  std::vector<PhonemeKeyframe> keyframes;
  for (const detail::TextLine& line : detail::content_lines(text)) {
    const auto fields = detail::split_fields(line.text);
    if (fields.size() != 4 && fields.size() != 5)
      throw VisemeDataError(
          file, line.number,
          "expected 4 or 5 fields (start duration symbol language [role]), found " + std::to_string(fields.size()));
    PhonemeKeyframe k;
    k.line = line.number;
    const auto start = detail::parse_number(fields[0]);
    if (!start) throw VisemeDataError(file, line.number, "start '" + std::string(fields[0]) + "' is not a number");
    const auto duration = detail::parse_number(fields[1]);
    if (!duration)
      throw VisemeDataError(file, line.number, "duration '" + std::string(fields[1]) + "' is not a number");
    if (*duration < 0.0) throw VisemeDataError(file, line.number, "duration is negative");
    k.start = *start;
    k.duration = *duration;
    k.symbol = fields[2];
    k.language = fields[3];
    if (fields.size() == 5) {
      const auto role = parse_role(fields[4]);
      if (fields[4] == "syllable")
        k.syllable = true;
      else if (role && *role != PhonemeRole::any)
        k.role = role;
      else
        throw VisemeDataError(
            file, line.number,
            "unknown role '" + std::string(fields[4]) + "' (onset, nucleus, coda, nasal or syllable)");
    }
    keyframes.push_back(std::move(k));
  }
  return keyframes;
}

std::vector<PhonemeKeyframe> read_phoneme_keyframes(const std::filesystem::path& file) {
  return parse_phoneme_keyframes(detail::read_text_file(file), file.string());
}

namespace {

// One keyframe's visemes, following the header's rule: a given role, a forced syllable, else a
// symbol the table maps unambiguously, else a syllable.
void keyframe_visemes(const PhonemeKeyframe& k, const VisemeTable& table, std::vector<TimedViseme>& out) {
  if (k.role) {
    out.push_back({k.start, k.duration, viseme_for(table, k.symbol, *k.role)});
    return;
  }
  if (!k.syllable)
    if (const auto v = find_viseme(table, k.symbol, PhonemeRole::any)) {
      out.push_back({k.start, k.duration, *v});
      return;
    }
  const auto pieces = syllable_visemes(table, k.symbol, k.start, k.duration);
  out.insert(out.end(), pieces.begin(), pieces.end());
}

}  // namespace

std::vector<TimedViseme> keyframes_to_visemes(std::span<const PhonemeKeyframe> keyframes, const VisemeLibrary& library,
                                              std::string_view file_name) {
  std::vector<TimedViseme> out;
  for (const PhonemeKeyframe& k : keyframes) {
    // Errors from the tables know the symbol but not where it was written; add the line.
    try {
      keyframe_visemes(k, library.table(k.language), out);
    } catch (const UnmappedSymbolError& e) {
      throw VisemeDataError(std::string(file_name), k.line, e.what());
    } catch (const std::invalid_argument& e) {
      throw VisemeDataError(std::string(file_name), k.line, e.what());
    }
  }
  std::stable_sort(out.begin(), out.end(),
                   [](const TimedViseme& a, const TimedViseme& b) { return a.start < b.start; });
  return out;
}

}  // namespace performer
