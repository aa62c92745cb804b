// Keeps third-party libraries (libpng inside OpenImageIO, for one) from printing their own lines
// on stderr while we read a file: the tools report every failure themselves, as one line.
#pragma once

namespace cli {

// While alive, file descriptor 2 points at /dev/null; the destructor restores it.
class QuietStderr {
 public:
  QuietStderr();
  ~QuietStderr();
  QuietStderr(const QuietStderr&) = delete;
  QuietStderr& operator=(const QuietStderr&) = delete;
  // The descriptor stderr had before: where the program's own output can still go meanwhile.
  int real_stderr() const { return saved_ >= 0 ? saved_ : 2; }

 private:
  int saved_ = -1;
};

}  // namespace cli
