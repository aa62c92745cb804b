#include "egl_display.h"

#include "egl_util.h"
#include "sanitizer_pin.h"
#include "glcontext/error.h"

#include <map>
#include <mutex>

namespace glc::detail {
namespace {

struct Registry {
  std::mutex mutex;
  std::map<EGLDisplay, int> leases;
};

// Never destroyed: a Context released during static destruction (e.g. one
// held in a global) must still find the registry alive.
Registry& registry() {
  static Registry* r = new Registry;
  return *r;
}

}  // namespace

EglDisplayLease::EglDisplayLease(EGLDisplay display) : display_(display) {
  Registry& r = registry();
  std::lock_guard lock(r.mutex);
  // eglInitialize on an already initialized display is a cheap no-op that
  // still reports the version, so call it every time.
  if (!eglInitialize(display_, &major_, &minor_)) throw GlError(egl_failure("eglInitialize"));
  ++r.leases[display_];
  pin_driver_libraries();
}

EglDisplayLease::~EglDisplayLease() {
  Registry& r = registry();
  std::lock_guard lock(r.mutex);
  auto it = r.leases.find(display_);
  if (it != r.leases.end() && --it->second == 0) {
    r.leases.erase(it);
    eglTerminate(display_);
  }
}

}  // namespace glc::detail
