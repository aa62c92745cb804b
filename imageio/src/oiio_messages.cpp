#include "oiio_messages.h"

namespace imageio::detail {

std::string oiio_message(std::string message, const char* fallback) {
  while (!message.empty() && (message.back() == '\n' || message.back() == ' ')) {
    message.pop_back();
  }
  return message.empty() ? std::string(fallback) : message;
}

}  // namespace imageio::detail
