#include "utf8_scan.h"

namespace performer::detail {

namespace {

struct Decoded {
  char32_t code_point = 0;
  std::size_t length = 0;  // 0: malformed
};

bool continuation(unsigned char byte) { return (byte & 0xC0) == 0x80; }

// The multi-byte lead forms: which bits mark the form, how long the sequence is, and the smallest
// code point it may carry (anything smaller is an overlong form, which UTF-8 forbids).
struct LeadForm {
  unsigned char mask;
  unsigned char marker;
  std::size_t length;
  char32_t smallest;
};
constexpr LeadForm kLeadForms[] = {{0xE0, 0xC0, 2, 0x80}, {0xF0, 0xE0, 3, 0x800}, {0xF8, 0xF0, 4, 0x10000}};

// One code point at `pos`; length 0 when the bytes there are not a valid, shortest-form sequence.
Decoded decode_at(std::string_view text, std::size_t pos) {
  const auto lead = static_cast<unsigned char>(text[pos]);
  if (lead < 0x80) return {lead, 1};
  for (const LeadForm& form : kLeadForms) {
    if ((lead & form.mask) != form.marker) continue;
    if (pos + form.length > text.size()) return {};
    char32_t value = lead & static_cast<unsigned char>(~form.mask);
    for (std::size_t i = 1; i < form.length; ++i) {
      const auto byte = static_cast<unsigned char>(text[pos + i]);
      if (!continuation(byte)) return {};
      value = (value << 6) | (byte & 0x3F);
    }
    if (value < form.smallest || value > 0x10FFFF || (value >= 0xD800 && value <= 0xDFFF)) return {};
    return {value, form.length};
  }
  return {};  // a stray continuation byte or 0xF8-0xFF
}

bool is_cjk_ideograph(char32_t c) {
  return (c >= 0x3005 && c <= 0x3007) ||    // 々 〆 〇
         (c >= 0x3400 && c <= 0x4DBF) ||    // extension A
         (c >= 0x4E00 && c <= 0x9FFF) ||    // unified ideographs
         (c >= 0xF900 && c <= 0xFAFF) ||    // compatibility ideographs
         (c >= 0x20000 && c <= 0x2FA1F) ||  // extensions B-F, compatibility supplement
         (c >= 0x30000 && c <= 0x323AF);    // extensions G, H
}

}  // namespace

std::optional<std::size_t> find_invalid_utf8(std::string_view text) {
  for (std::size_t pos = 0; pos < text.size();) {
    const Decoded d = decode_at(text, pos);
    if (d.length == 0) return pos;
    pos += d.length;
  }
  return std::nullopt;
}

std::optional<std::string_view> find_cjk_ideograph(std::string_view text) {
  for (std::size_t pos = 0; pos < text.size();) {
    const Decoded d = decode_at(text, pos);
    if (d.length == 0) return std::nullopt;  // not UTF-8: find_invalid_utf8 reports it
    if (is_cjk_ideograph(d.code_point)) return text.substr(pos, d.length);
    pos += d.length;
  }
  return std::nullopt;
}

}  // namespace performer::detail
