#pragma once

#include <string>

namespace imageio::detail {

// OpenImageIO reports errors as possibly multi-line text, sometimes empty.
// Returns `message`, or `fallback` when it is empty; IoError folds the lines.
std::string oiio_message(std::string message, const char* fallback);

}  // namespace imageio::detail
