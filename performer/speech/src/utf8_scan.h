// Just enough UTF-8 for checking TTS input before the engine sees it: whether the text is well
// formed and where its first CJK ideograph is (a voice that reads pinyin or kana cannot read hanzi
// or kanji, and espeak-ng would otherwise spell them out as "Chinese letter" in English).
#pragma once

#include <cstddef>
#include <optional>
#include <string_view>

namespace performer::detail {

// The byte offset of the first malformed sequence (bad lead or continuation byte, truncation,
// overlong form, surrogate, beyond U+10FFFF); nullopt when the text is well-formed UTF-8.
std::optional<std::size_t> find_invalid_utf8(std::string_view text);

// The first CJK ideograph of well-formed UTF-8 text: the bytes of that character (a view into
// `text`); nullopt when there is none. Ideographs are the Unified Ideographs blocks (basic,
// extensions A-H), the compatibility ideographs and the marks that stand in kanji text (々 〆 〇).
std::optional<std::string_view> find_cjk_ideograph(std::string_view text);

}  // namespace performer::detail
