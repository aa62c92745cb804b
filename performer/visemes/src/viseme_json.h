// A minimal JSON reader: enough to walk Rhubarb Lip Sync's JSON output (objects, arrays, strings,
// numbers; anything else skipped) and say on which line it went wrong. Private to the library; the
// project takes no JSON dependency for one fixed document shape.
#pragma once

#include <string>
#include <string_view>

namespace performer::detail {

class JsonCursor {
 public:
  JsonCursor(std::string_view text, std::string file_name);

  const std::string& file_name() const { return file_; }
  int line() const { return line_; }  // of the next unread character
  // The next non-blank character without consuming it; '\0' at the end of the text.
  char peek();
  // Consumes `c` if it is the next non-blank character.
  bool consume(char c);
  // Consumes `c` or throws "expected <what>".
  void expect(char c, std::string_view what);
  std::string read_string();
  double read_number();
  // Skips one value of any kind (nesting limited, so hostile input cannot exhaust the stack).
  void skip_value();
  // Throws unless only blanks are left.
  void expect_end();
  // Throws VisemeDataError(file, line(), problem).
  [[noreturn]] void fail(const std::string& problem) const;

 private:
  void skip_blanks();
  void skip_value(int depth);
  void skip_word(std::string_view word);

  std::string_view text_;
  std::string file_;
  std::size_t pos_ = 0;
  int line_ = 1;
};

}  // namespace performer::detail
