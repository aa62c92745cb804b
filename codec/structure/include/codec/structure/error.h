#pragma once
#include <stdexcept>
#include <string>

namespace codec {

// Every encoder failure a user can cause or act on: one line, no trailing newline.
class EncodeError : public std::runtime_error {
 public:
  explicit EncodeError(const std::string& what) : std::runtime_error(what) {}
};

}  // namespace codec
