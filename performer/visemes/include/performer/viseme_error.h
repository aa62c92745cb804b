// The two ways lip-sync input goes wrong: a data file that does not read (table, keyframes, Rhubarb
// cues) and a phoneme no table maps. Kept apart so a caller can tell a typo in a file from a
// language that lacks a symbol.
#pragma once

#include <stdexcept>
#include <string>

#include "performer/phoneme_role.h"

namespace performer {

// A malformed or unreadable data file. what() is "FILE:LINE: problem", or "FILE: problem" when no
// line applies (the file cannot be opened, or a whole-file check failed).
class VisemeDataError : public std::runtime_error {
 public:
  VisemeDataError(std::string file, int line, std::string problem);
  const std::string& file() const { return file_; }
  int line() const { return line_; }  // 1-based; 0 when the problem is not tied to a line
  const std::string& problem() const { return problem_; }

 private:
  std::string file_;
  int line_;
  std::string problem_;
};

// A symbol the language's table does not map in the asked role (or maps to different visemes in
// different roles when asked for "any"). what() names language, symbol and role.
class UnmappedSymbolError : public std::runtime_error {
 public:
  UnmappedSymbolError(std::string language, std::string symbol, PhonemeRole role, const std::string& detail = {});
  const std::string& language() const { return language_; }
  const std::string& symbol() const { return symbol_; }
  PhonemeRole role() const { return role_; }

 private:
  std::string language_;
  std::string symbol_;
  PhonemeRole role_;
};

}  // namespace performer
