#include "performer/espeak_tts.h"

#include <algorithm>
#include <stdexcept>
#include <utility>

#include "espeak_engine.h"
#include "utf8_scan.h"

namespace performer {

namespace {

struct Language {
  std::string_view name;  // ours and espeak-ng's voice name
  // Why the language refuses CJK ideographs; empty when it reads them.
  std::string_view ideographs_refused;
};

constexpr Language kLanguages[] = {
    {"yue", ""},
    {"cmn-latn-pinyin", "it reads Hanyu Pinyin with tone digits (\"ni3 hao3\"); convert the hanzi to pinyin first"},
    {"ja", "it reads kana only (espeak-ng has no kanji readings); write the text in kana"},
    {"en-us", ""},
};

std::string language_list() {
  std::string list;
  for (const Language& l : kLanguages) list += (list.empty() ? "" : ", ") + std::string(l.name);
  return list;
}

const Language& find_language(std::string_view name) {
  for (const Language& l : kLanguages)
    if (l.name == name) return l;
  throw std::invalid_argument("unknown speech language '" + std::string(name) + "' (have: " + language_list() + ")");
}

void check_text(std::string_view text, const Language& language) {
  if (text.find_first_not_of(" \t\r\n\f\v") == std::string_view::npos)
    throw std::invalid_argument("speech text is empty");
  if (const auto bad = detail::find_invalid_utf8(text))
    throw std::invalid_argument("speech text is not UTF-8 (malformed at byte " + std::to_string(*bad) + ")");
  if (language.ideographs_refused.empty()) return;
  if (const auto ideograph = detail::find_cjk_ideograph(text))
    throw std::invalid_argument("speech language '" + std::string(language.name) +
                                "' cannot read CJK ideographs such as '" + std::string(*ideograph) +
                                "': " + std::string(language.ideographs_refused));
}

// espeak-ng's pause phonemes are all named "_..." ("_", "_:", "_|", "_!") or "||".
bool is_pause(std::string_view name) { return name.starts_with('_') || name == "||"; }

// Text that is all punctuation comes back as a few pauses and a handful of silent samples.
void check_spoken(const detail::EspeakAudio& audio, std::string_view language) {
  const bool said_something =
      std::any_of(audio.marks.begin(), audio.marks.end(), [](const PhonemeMark& m) { return !is_pause(m.name); });
  if (!said_something || audio.samples.empty())
    throw std::invalid_argument("espeak-ng voice '" + std::string(language) +
                                "' found nothing to say in the text (only punctuation or blanks?)");
  if (audio.sample_rate <= 0) throw std::runtime_error("espeak-ng reported no sample rate");
}

}  // namespace

bool EspeakTts::built() { return true; }

EspeakTts::EspeakTts() { detail::espeak_start(); }

Speech EspeakTts::speak(std::string_view text, std::string_view language) {
  const Language& lang = find_language(language);
  check_text(text, lang);
  detail::EspeakAudio audio = detail::espeak_synthesize(std::string(lang.name), std::string(text));
  check_spoken(audio, lang.name);
  Speech speech;
  speech.sample_rate = audio.sample_rate;
  speech.samples = std::move(audio.samples);
  speech.phonemes = phonemes_from_marks(audio.marks, speech.duration());
  return speech;
}

std::vector<std::string> EspeakTts::languages() const {
  std::vector<std::string> names;
  for (const Language& l : kLanguages) names.emplace_back(l.name);
  return names;
}

}  // namespace performer
