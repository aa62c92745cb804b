#include "imageio/error.h"

namespace imageio {
namespace {

// Folds every run of line breaks into "; " and drops trailing ones, so that a
// multi-line message from a library (or a path with a newline in it) still
// prints as a single line.
std::string one_line(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  bool pending_break = false;
  for (char ch : text) {
    if (ch == '\n' || ch == '\r') {
      pending_break = true;
      continue;
    }
    if (pending_break && !out.empty()) out += "; ";
    pending_break = false;
    out += ch;
  }
  return out;
}

}  // namespace

IoError::IoError(const std::string& path, const std::string& problem)
    : std::runtime_error(one_line(path + ": " + problem)), path_(path) {}

}  // namespace imageio
