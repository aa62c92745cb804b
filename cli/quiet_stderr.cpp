#include "quiet_stderr.h"

#include <fcntl.h>
#include <unistd.h>

#include <cstdio>

namespace cli {

QuietStderr::QuietStderr() {
  std::fflush(stderr);
  saved_ = ::dup(2);
  const int null_fd = ::open("/dev/null", O_WRONLY | O_CLOEXEC);
  if (saved_ >= 0 && null_fd >= 0) ::dup2(null_fd, 2);
  if (null_fd >= 0) ::close(null_fd);
}

QuietStderr::~QuietStderr() {
  if (saved_ < 0) return;
  std::fflush(stderr);
  ::dup2(saved_, 2);
  ::close(saved_);
}

}  // namespace cli
