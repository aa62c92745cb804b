// Which phonemes a written syllable is made of (thesis 3.4.2: "decomposing a syllable into its
// onset, nucleus and coda"), using only the symbols and roles of the language's table: "zung1" in
// Cantonese is onset z, nucleus u, coda ng; "hao" in Mandarin is onset h, nucleus a + o.
//
// Shape: onset* nucleus+ coda?, or a single nasal (Cantonese m, ng). Trailing tone digits (LSHK
// "zung1", pinyin "hao3") are ignored. When several splits fit, the one with the fewest nucleus
// symbols wins, then the fewest onset symbols, then the one with a coda: Cantonese "nei" is n + e +
// coda i, not n + nucleus "e i"; "gwaa" is gw + aa, not g + w + aa.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "performer/phoneme_role.h"
#include "performer/viseme_table.h"

namespace performer {

struct SyllablePhoneme {
  std::string symbol;
  PhonemeRole role = PhonemeRole::any;  // onset, nucleus, coda or nasal
};

// The syllable without trailing ASCII digits.
std::string_view strip_tone(std::string_view syllable);

// The phonemes in spoken order, each tagged with its role; nullopt when no split fits.
std::optional<std::vector<SyllablePhoneme>> parse_syllable(const VisemeTable& table, std::string_view syllable);

}  // namespace performer
