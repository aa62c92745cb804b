// The OpenImageIO module's entry points (see oiio_module.h): the reader and writer, with any
// exception turned into a status and a one-line problem, since exceptions must not cross dlopen.

#include <algorithm>
#include <cstddef>
#include <cstring>
#include <exception>
#include <string>
#include <type_traits>

#include "imageio/error.h"
#include "oiio_codec.h"
#include "oiio_module.h"

namespace {

void copy_problem(const std::string& text, char* problem, std::size_t problem_size) {
  if (problem_size == 0) return;
  const std::size_t n = std::min(text.size(), problem_size - 1);
  std::memcpy(problem, text.data(), n);
  problem[n] = '\0';
}

// IoError's text is "PATH: problem"; the caller adds the path again, so keep only the problem.
std::string problem_of(const imageio::IoError& e) {
  const std::string text = e.what();
  const std::string prefix = e.path() + ": ";
  return text.compare(0, prefix.size(), prefix) == 0 ? text.substr(prefix.size()) : text;
}

template <typename Work>
int guarded(Work work, char* problem, std::size_t problem_size) {
  try {
    work();
    return imageio::detail::kModuleOk;
  } catch (const imageio::IoError& e) {
    copy_problem(problem_of(e), problem, problem_size);
  } catch (const std::exception& e) {
    copy_problem(e.what(), problem, problem_size);
  } catch (...) {
    copy_problem("unknown error inside OpenImageIO", problem, problem_size);
  }
  return imageio::detail::kModuleFailed;
}

}  // namespace

extern "C" int gpuj2k_oiio_read(const char* path, imageio::Image* image, char* problem, std::size_t problem_size) {
  return guarded([&] { *image = imageio::detail::read_with_oiio(path); }, problem, problem_size);
}

extern "C" int gpuj2k_oiio_write(const char* path, const imageio::Image* image, char* problem,
                                 std::size_t problem_size) {
  return guarded([&] { imageio::detail::write_with_oiio(path, *image); }, problem, problem_size);
}

// The loader checks the types through these aliases, so a changed signature fails to compile.
static_assert(std::is_same_v<decltype(&gpuj2k_oiio_read), imageio::detail::ModuleRead>);
static_assert(std::is_same_v<decltype(&gpuj2k_oiio_write), imageio::detail::ModuleWrite>);
