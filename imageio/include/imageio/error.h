#pragma once

#include <stdexcept>
#include <string>

namespace imageio {

// Every failure to read or write an image is reported as an IoError whose
// message is a single line "PATH: problem", so command-line tools can print
// what() as-is and scripts can grep for the file that failed.
class IoError : public std::runtime_error {
 public:
  // Line breaks inside `problem` (library messages often contain them) are
  // folded into "; " so the one-line guarantee holds whatever we are given.
  IoError(const std::string& path, const std::string& problem);

  const std::string& path() const noexcept { return path_; }

 private:
  std::string path_;
};

}  // namespace imageio
