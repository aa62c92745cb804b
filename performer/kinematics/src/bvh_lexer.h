// Splits BVH text into tokens that remember their line. Private to the reader.
//
// BVH is mostly free-form (the hierarchy could be one long line) except for motion rows, which are
// delimited by line ends; keeping the line on every token serves both, and gives error messages
// their line numbers for free.
#pragma once

#include <cstddef>
#include <string_view>

namespace performer::detail {

struct Token {
  std::string_view text;  // empty only at the end of the input
  int line = 0;           // 1-based line the token starts on
  bool end() const { return text.empty(); }
};

class BvhLexer {
 public:
  explicit BvhLexer(std::string_view text);

  Token next();
  Token peek() const;
  // Number of the last line that holds anything: where "unexpected end of file" is reported.
  int last_line() const;

 private:
  // Moves past blanks and line ends, counting lines.
  void skip_blanks(std::size_t& pos, int& line) const;
  Token scan(std::size_t& pos, int& line) const;

  std::string_view text_;
  std::size_t pos_ = 0;
  int line_ = 1;
};

}  // namespace performer::detail
