#pragma once
#include <stdexcept>
#include <string>

namespace dwt {

// Raised for invalid transform requests (impossible level counts, unsupported kernel on a backend,
// empty planes). The message is one line a user can act on.
class DwtError : public std::runtime_error {
 public:
  explicit DwtError(const std::string& what) : std::runtime_error(what) {}
};

}  // namespace dwt
