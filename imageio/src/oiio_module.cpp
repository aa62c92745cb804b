// Finding and opening the OpenImageIO module (see oiio_module.h).

#include "oiio_module.h"

#include <dlfcn.h>
#include <unistd.h>

#include <cstdlib>
#include <string>
#include <vector>

#include "imageio/error.h"
#include "oiio_codec.h"

#ifndef GPUJ2K_OIIO_MODULE_FILE
#error "GPUJ2K_OIIO_MODULE_FILE (the module's file name) must be defined by the build"
#endif

namespace imageio::detail {

#ifdef GPUJ2K_OIIO_LINKED
// Sanitizer builds link the reader and writer in (imageio/CMakeLists.txt says why).
Image read_through_module(const std::string& path) { return read_with_oiio(path); }
void write_through_module(const std::string& path, const Image& image) { write_with_oiio(path, image); }
#else
namespace {

struct Module {
  ModuleRead read = nullptr;
  ModuleWrite write = nullptr;
  std::string failure;  // why it could not be loaded; empty when it was
};

std::string program_directory() {
  std::vector<char> buffer(4096);
  const ssize_t n = readlink("/proc/self/exe", buffer.data(), buffer.size() - 1);
  if (n <= 0) return {};
  const std::string program(buffer.data(), static_cast<std::size_t>(n));
  const std::size_t slash = program.rfind('/');
  return slash == std::string::npos ? std::string() : program.substr(0, slash + 1);
}

// The folder of the library or program this code is linked into (libgpuj2k.so, installed beside
// the module in lib/, or a program in the build's bin/).
std::string own_directory() {
  Dl_info info{};
  if (dladdr(reinterpret_cast<void*>(&own_directory), &info) == 0 || info.dli_fname == nullptr) return {};
  const std::string file = info.dli_fname;
  const std::size_t slash = file.rfind('/');
  return slash == std::string::npos ? std::string() : file.substr(0, slash + 1);
}

std::vector<std::string> candidates() {
  if (const char* forced = std::getenv("GPUJ2K_OIIO_MODULE"); forced != nullptr && *forced != '\0') return {forced};
  std::vector<std::string> list;
  if (const std::string dir = program_directory(); !dir.empty()) {
    list.push_back(dir + GPUJ2K_OIIO_MODULE_FILE);
    list.push_back(dir + "../" GPUJ2K_INSTALL_LIBDIR "/" GPUJ2K_OIIO_MODULE_FILE);  // an installed program
  }
  if (const std::string dir = own_directory(); !dir.empty() && dir != program_directory())
    list.push_back(dir + GPUJ2K_OIIO_MODULE_FILE);
  list.push_back(GPUJ2K_OIIO_MODULE_FILE);  // LD_LIBRARY_PATH and the system's directories
  return list;
}

Module load() {
  Module module;
  std::string errors;
  for (const std::string& candidate : candidates()) {
    void* handle = dlopen(candidate.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (handle == nullptr) {
      const char* why = dlerror();
      errors += (errors.empty() ? "" : "; ") + std::string(why != nullptr ? why : candidate.c_str());
      continue;
    }
    // Never closed: the module stays for the life of the process, like a linked library.
    module.read = reinterpret_cast<ModuleRead>(dlsym(handle, kReadSymbol));
    module.write = reinterpret_cast<ModuleWrite>(dlsym(handle, kWriteSymbol));
    if (module.read != nullptr && module.write != nullptr) return module;
    errors += (errors.empty() ? "" : "; ") + candidate + " lacks the reader or writer entry point";
  }
  module = Module{};
  module.failure = "this format needs OpenImageIO, whose module " + std::string(GPUJ2K_OIIO_MODULE_FILE) +
                   " could not be loaded (" + errors + ")";
  return module;
}

const Module& module_for(const std::string& path) {
  static const Module module = load();  // once per process, thread-safe (a function-local static)
  if (!module.failure.empty()) throw IoError(path, module.failure);
  return module;
}

}  // namespace

Image read_through_module(const std::string& path) {
  const Module& module = module_for(path);
  Image image;
  char problem[1024] = {};
  if (module.read(path.c_str(), &image, problem, sizeof problem) != kModuleOk) throw IoError(path, problem);
  return image;
}

void write_through_module(const std::string& path, const Image& image) {
  const Module& module = module_for(path);
  char problem[1024] = {};
  if (module.write(path.c_str(), &image, problem, sizeof problem) != kModuleOk) throw IoError(path, problem);
}
#endif

}  // namespace imageio::detail
