#pragma once
#include <stdexcept>
#include <string>

namespace wavelet_apps {

// Raised for anything a user typed wrong or a file that cannot be used: one line naming the culprit.
class AppError : public std::runtime_error {
 public:
  explicit AppError(const std::string& what) : std::runtime_error(what) {}
};

}  // namespace wavelet_apps
