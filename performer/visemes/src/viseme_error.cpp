#include "performer/viseme_error.h"

#include <utility>

namespace performer {

VisemeDataError::VisemeDataError(std::string file, int line, std::string problem)
    : std::runtime_error(line > 0 ? file + ":" + std::to_string(line) + ": " + problem : file + ": " + problem),
      file_(std::move(file)),
      line_(line),
      problem_(std::move(problem)) {}

namespace {

std::string unmapped_message(const std::string& language, const std::string& symbol, PhonemeRole role,
                             const std::string& detail) {
  std::string message = "no viseme for '" + symbol + "'";
  if (role != PhonemeRole::any) message += " as " + std::string(role_name(role));
  message += " in language '" + language + "'";
  if (!detail.empty()) message += ": " + detail;
  return message;
}

}  // namespace

UnmappedSymbolError::UnmappedSymbolError(std::string language, std::string symbol, PhonemeRole role,
                                         const std::string& detail)
    : std::runtime_error(unmapped_message(language, symbol, role, detail)),
      language_(std::move(language)),
      symbol_(std::move(symbol)),
      role_(role) {}

}  // namespace performer
