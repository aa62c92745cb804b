#include "bvh_lexer.h"

namespace performer::detail {

namespace {

// Blanks other than line ends. Other control characters stay inside tokens, so they surface as
// "non-numeric" or "unknown keyword" errors instead of being silently skipped.
bool is_blank(char c) { return c == ' ' || c == '\t' || c == '\f' || c == '\v'; }

bool is_brace(char c) { return c == '{' || c == '}'; }

}  // namespace

BvhLexer::BvhLexer(std::string_view text) : text_(text) {
  // Some Windows tools write a UTF-8 byte order mark; it is not part of the first keyword.
  if (text_.substr(0, 3) == "\xEF\xBB\xBF") pos_ = 3;
}

void BvhLexer::skip_blanks(std::size_t& pos, int& line) const {
  while (pos < text_.size()) {
    const char c = text_[pos];
    if (c == '\n') {
      ++line;
    } else if (c == '\r') {
      // CRLF counts once (at its LF); a lone CR (classic Mac) is a line end of its own. Real files
      // mix both: the CMU conversions end some lines with CRLF and others with LF.
      if (pos + 1 >= text_.size() || text_[pos + 1] != '\n') ++line;
    } else if (!is_blank(c)) {
      return;
    }
    ++pos;
  }
}

Token BvhLexer::scan(std::size_t& pos, int& line) const {
  skip_blanks(pos, line);
  if (pos >= text_.size()) return Token{{}, line};
  const std::size_t start = pos;
  // Braces are tokens even when glued to a word ("Hips{"), which some exporters write.
  if (is_brace(text_[pos])) {
    ++pos;
  } else {
    while (pos < text_.size() && !is_blank(text_[pos]) && text_[pos] != '\n' && text_[pos] != '\r' &&
           !is_brace(text_[pos]))
      ++pos;
  }
  return Token{text_.substr(start, pos - start), line};
}

Token BvhLexer::next() { return scan(pos_, line_); }

Token BvhLexer::peek() const {
  std::size_t pos = pos_;
  int line = line_;
  return scan(pos, line);
}

int BvhLexer::last_line() const {
  int line = 1;
  int last = 1;
  for (std::size_t pos = 0; pos < text_.size(); ++pos) {
    const char c = text_[pos];
    if (c == '\n' || (c == '\r' && (pos + 1 >= text_.size() || text_[pos + 1] != '\n'))) {
      ++line;
    } else if (c != '\r' && !is_blank(c)) {
      last = line;
    }
  }
  return last;
}

}  // namespace performer::detail
