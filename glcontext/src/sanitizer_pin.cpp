#include "sanitizer_pin.h"

#include "base/sanitizers.h"

#ifdef GPUJ2K_ADDRESS_SANITIZER
#include <dlfcn.h>
#include <link.h>

#include <cstring>
#endif

namespace glc::detail {

#ifdef GPUJ2K_ADDRESS_SANITIZER
namespace {

// Mesa's DRI megadriver (swrast_dri.so, ..._dri.so), its newer libgallium
// split, and libOSMesa.
bool is_driver_library(const char* path) {
  return std::strstr(path, "_dri.so") != nullptr || std::strstr(path, "libgallium") != nullptr ||
         std::strstr(path, "libOSMesa") != nullptr;
}

int pin_one(dl_phdr_info* info, size_t, void*) {
  if (info->dlpi_name != nullptr && is_driver_library(info->dlpi_name)) {
    // RTLD_NOLOAD only bumps the reference count of an already loaded
    // library; the handle is deliberately never closed.
    dlopen(info->dlpi_name, RTLD_NOW | RTLD_NOLOAD);
  }
  return 0;
}

}  // namespace

void pin_driver_libraries() noexcept { dl_iterate_phdr(pin_one, nullptr); }
#else
void pin_driver_libraries() noexcept {}
#endif

}  // namespace glc::detail
