#include "performer/syllable_parse.h"

#include <algorithm>
#include <tuple>

namespace performer {

namespace {

// The distinct symbols that may stand in a role.
std::vector<std::string_view> symbols_for(const VisemeTable& table, PhonemeRole role) {
  std::vector<std::string_view> out;
  for (const VisemeEntry& e : table.entries)
    if ((e.role == role || e.role == PhonemeRole::any) &&
        std::find(out.begin(), out.end(), std::string_view(e.symbol)) == out.end())
      out.push_back(e.symbol);
  return out;
}

// Exhaustive search over onset* nucleus+ coda?; syllables are a few letters, so this stays tiny.
class SplitSearch {
 public:
  SplitSearch(const VisemeTable& table, std::string_view text)
      : text_(text),
        onsets_(symbols_for(table, PhonemeRole::onset)),
        nuclei_(symbols_for(table, PhonemeRole::nucleus)),
        codas_(symbols_for(table, PhonemeRole::coda)) {}

  std::optional<std::vector<SyllablePhoneme>> run() {
    onset(0);
    return best_;
  }

 private:
  void onset(std::size_t pos) {
    nucleus(pos);
    for (std::string_view s : onsets_)
      if (text_.substr(pos).starts_with(s)) {
        current_.push_back({std::string(s), PhonemeRole::onset});
        onset(pos + s.size());
        current_.pop_back();
      }
  }

  void nucleus(std::size_t pos) {
    for (std::string_view s : nuclei_) {
      if (!text_.substr(pos).starts_with(s)) continue;
      current_.push_back({std::string(s), PhonemeRole::nucleus});
      const std::size_t next = pos + s.size();
      if (next == text_.size()) offer();
      for (std::string_view c : codas_)
        if (text_.substr(next) == c) {
          current_.push_back({std::string(c), PhonemeRole::coda});
          offer();
          current_.pop_back();
        }
      nucleus(next);
      current_.pop_back();
    }
  }

  // Fewest nucleus symbols, then fewest onset symbols, then a coda rather than none (see header).
  static std::tuple<int, int, int> rank(const std::vector<SyllablePhoneme>& parse) {
    int onsets = 0, nuclei = 0, codas = 0;
    for (const SyllablePhoneme& p : parse) {
      onsets += p.role == PhonemeRole::onset;
      nuclei += p.role == PhonemeRole::nucleus;
      codas += p.role == PhonemeRole::coda;
    }
    return {nuclei, onsets, -codas};
  }

  void offer() {
    if (!best_ || rank(current_) < rank(*best_)) best_ = current_;
  }

  std::string_view text_;
  std::vector<std::string_view> onsets_, nuclei_, codas_;
  std::vector<SyllablePhoneme> current_;
  std::optional<std::vector<SyllablePhoneme>> best_;
};

}  // namespace

std::string_view strip_tone(std::string_view syllable) {
  while (!syllable.empty() && syllable.back() >= '0' && syllable.back() <= '9') syllable.remove_suffix(1);
  return syllable;
}

std::optional<std::vector<SyllablePhoneme>> parse_syllable(const VisemeTable& table, std::string_view syllable) {
  const std::string_view text = strip_tone(syllable);
  if (text.empty()) return std::nullopt;
  // A syllabic nasal is a whole syllable of its own kind (Table 3.4); only entries marked nasal
  // count, so a wildcard entry does not turn every lone consonant into one.
  for (const VisemeEntry& e : table.entries)
    if (e.role == PhonemeRole::nasal && e.symbol == text)
      return std::vector<SyllablePhoneme>{{e.symbol, PhonemeRole::nasal}};
  return SplitSearch(table, text).run();
}

}  // namespace performer
