#include "viseme_json.h"

#include <charconv>
#include <cmath>
#include <cstdint>
#include <utility>

#include "performer/viseme_error.h"

namespace performer::detail {

namespace {

constexpr int kMaxDepth = 64;

void append_utf8(std::string& out, std::uint32_t cp) {
  if (cp < 0x80) {
    out += static_cast<char>(cp);
  } else if (cp < 0x800) {
    out += static_cast<char>(0xC0 | (cp >> 6));
    out += static_cast<char>(0x80 | (cp & 0x3F));
  } else if (cp < 0x10000) {
    out += static_cast<char>(0xE0 | (cp >> 12));
    out += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
    out += static_cast<char>(0x80 | (cp & 0x3F));
  } else {
    out += static_cast<char>(0xF0 | (cp >> 18));
    out += static_cast<char>(0x80 | ((cp >> 12) & 0x3F));
    out += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
    out += static_cast<char>(0x80 | (cp & 0x3F));
  }
}

}  // namespace

JsonCursor::JsonCursor(std::string_view text, std::string file_name) : text_(text), file_(std::move(file_name)) {
  constexpr std::string_view kBom = "\xEF\xBB\xBF";
  if (text_.starts_with(kBom)) pos_ = kBom.size();
}

void JsonCursor::fail(const std::string& problem) const { throw VisemeDataError(file_, line_, problem); }

void JsonCursor::skip_blanks() {
  while (pos_ < text_.size()) {
    const char c = text_[pos_];
    if (c == '\n') {
      ++line_;
    } else if (c == '\r') {
      // CRLF counts once: the LF will not count again.
      if (pos_ + 1 >= text_.size() || text_[pos_ + 1] != '\n') ++line_;
    } else if (c != ' ' && c != '\t') {
      return;
    }
    ++pos_;
  }
}

char JsonCursor::peek() {
  skip_blanks();
  return pos_ < text_.size() ? text_[pos_] : '\0';
}

bool JsonCursor::consume(char c) {
  if (peek() != c) return false;
  ++pos_;
  return true;
}

void JsonCursor::expect(char c, std::string_view what) {
  if (!consume(c)) fail("expected " + std::string(what));
}

void JsonCursor::expect_end() {
  if (peek() != '\0') fail("unexpected text after the JSON document");
}

std::string JsonCursor::read_string() {
  expect('"', "a string");
  std::string out;
  while (true) {
    if (pos_ >= text_.size()) fail("unterminated string");
    const char c = text_[pos_++];
    if (c == '"') return out;
    if (static_cast<unsigned char>(c) < 0x20) fail("control character in string");
    if (c != '\\') {
      out += c;
      continue;
    }
    if (pos_ >= text_.size()) fail("unterminated string");
    const char e = text_[pos_++];
    switch (e) {
      case '"':
        out += '"';
        break;
      case '\\':
        out += '\\';
        break;
      case '/':
        out += '/';
        break;
      case 'b':
        out += '\b';
        break;
      case 'f':
        out += '\f';
        break;
      case 'n':
        out += '\n';
        break;
      case 'r':
        out += '\r';
        break;
      case 't':
        out += '\t';
        break;
      case 'u': {
        const auto hex4 = [&]() {
          std::uint32_t v = 0;
          if (pos_ + 4 > text_.size()) fail("short \\u escape");
          const auto [ptr, ec] = std::from_chars(text_.data() + pos_, text_.data() + pos_ + 4, v, 16);
          if (ec != std::errc() || ptr != text_.data() + pos_ + 4) fail("bad \\u escape");
          pos_ += 4;
          return v;
        };
        std::uint32_t cp = hex4();
        if (cp >= 0xD800 && cp < 0xDC00) {  // a surrogate pair spells one code point above U+FFFF
          if (pos_ + 2 > text_.size() || text_[pos_] != '\\' || text_[pos_ + 1] != 'u') fail("lone surrogate");
          pos_ += 2;
          const std::uint32_t low = hex4();
          if (low < 0xDC00 || low >= 0xE000) fail("bad surrogate pair");
          cp = 0x10000 + ((cp - 0xD800) << 10) + (low - 0xDC00);
        } else if (cp >= 0xDC00 && cp < 0xE000) {
          fail("lone surrogate");
        }
        append_utf8(out, cp);
        break;
      }
      default:
        fail(std::string("bad escape \\") + e);
    }
  }
}

double JsonCursor::read_number() {
  const char first = peek();
  if (first != '-' && (first < '0' || first > '9')) fail("expected a number");
  std::size_t end = pos_;
  while (end < text_.size() && (std::string_view("+-.eE0123456789").find(text_[end]) != std::string_view::npos)) ++end;
  double value = 0.0;
  const auto [ptr, ec] = std::from_chars(text_.data() + pos_, text_.data() + end, value);
  if (ec != std::errc() || ptr != text_.data() + end || !std::isfinite(value))
    fail("bad number '" + std::string(text_.substr(pos_, end - pos_)) + "'");
  pos_ = end;
  return value;
}

void JsonCursor::skip_word(std::string_view word) {
  if (text_.substr(pos_, word.size()) != word) fail("unexpected character");
  pos_ += word.size();
}

void JsonCursor::skip_value() { skip_value(0); }

void JsonCursor::skip_value(int depth) {
  if (depth > kMaxDepth) fail("nesting too deep");
  const char c = peek();
  if (c == '"') {
    read_string();
  } else if (c == '{') {
    ++pos_;
    if (consume('}')) return;
    do {
      read_string();
      expect(':', "':'");
      skip_value(depth + 1);
    } while (consume(','));
    expect('}', "',' or '}'");
  } else if (c == '[') {
    ++pos_;
    if (consume(']')) return;
    do skip_value(depth + 1);
    while (consume(','));
    expect(']', "',' or ']'");
  } else if (c == 't') {
    skip_word("true");
  } else if (c == 'f') {
    skip_word("false");
  } else if (c == 'n') {
    skip_word("null");
  } else if (c == '\0') {
    fail("unexpected end of file");
  } else {
    read_number();
  }
}

}  // namespace performer::detail
