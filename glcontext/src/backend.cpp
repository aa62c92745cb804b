#include "backend.h"

namespace glc::detail {
namespace {

// The backend this library last bound on this thread (null: none). A Context
// must not be destroyed while current on another thread, or that thread's
// entry would dangle (EGL/OSMesa forbid it in spirit too).
thread_local Backend* t_current = nullptr;

}  // namespace

void Backend::make_current() {
  if (t_current != nullptr && t_current != this) t_current->release_current();
  // Bind even when already current: it is cheap and also repairs a binding
  // changed behind our back.
  bind();
  t_current = this;
}

void Backend::release_current() noexcept {
  if (t_current != this) return;
  unbind();
  t_current = nullptr;
}

}  // namespace glc::detail
