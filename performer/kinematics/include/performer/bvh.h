// Reader for Biovision Hierarchy (BVH) motion capture files.
//
// Accepted: any mix of tabs and spaces, LF / CRLF / CR line ends, blank lines, trailing blanks, a
// UTF-8 byte order mark, keywords in any letter case, CHANNELS with 0..6 distinct channels in any
// order, joints without CHANNELS, and several ROOT hierarchies (one Skeleton whose roots all have
// parent -1; their channels follow each other in the motion rows in file order).
// Each motion row must sit on one line: a row with too few or too many values is an error, as is a
// row count that differs from "Frames:".
#pragma once

#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>

#include "performer/skeleton.h"

namespace performer {

// A malformed or unreadable file. what() is "FILE:LINE: problem" (or "FILE: problem" when no line
// applies, e.g. the file cannot be opened), lines counted from 1.
class BvhError : public std::runtime_error {
 public:
  BvhError(std::string file, int line, std::string problem);
  const std::string& file() const { return file_; }
  int line() const { return line_; }  // 0 when the problem is not tied to a line
  const std::string& problem() const { return problem_; }

 private:
  std::string file_;
  int line_;
  std::string problem_;
};

struct Bvh {
  Skeleton skeleton;
  Motion motion;
};

// Parses BVH text; `file_name` only labels error messages.
Bvh parse_bvh(std::string_view text, std::string_view file_name = "<bvh>");

// Reads and parses a file. Throws BvhError for unreadable files as well as malformed ones.
Bvh read_bvh(const std::filesystem::path& path);

}  // namespace performer
