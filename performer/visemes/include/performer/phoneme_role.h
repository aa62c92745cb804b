// The place a phoneme takes in its syllable (thesis 3.4.2: "a syllable unit can be subdivided into
// an optional onset, a nucleus and an optional coda"). Viseme tables key on it because the same
// letter can look different in different places (Cantonese nucleus u is O, coda u is UH).
#pragma once

#include <optional>
#include <string_view>

namespace performer {

enum class PhonemeRole {
  any,      // in a table: fits every place; in a query: "whichever, as long as they agree"
  onset,    // the consonant(s) starting the syllable
  nucleus,  // the vowel core
  coda,     // the consonant ending it
  nasal,    // a syllabic nasal that is the whole syllable (Cantonese m, ng; thesis Table 3.4)
};

std::string_view role_name(PhonemeRole role);

// "any", "onset", "nucleus", "coda", "nasal"; nullopt for anything else.
std::optional<PhonemeRole> parse_role(std::string_view text);

}  // namespace performer
