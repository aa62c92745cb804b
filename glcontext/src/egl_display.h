// Internal: reference-counted eglInitialize/eglTerminate.
//
// EGL hands out one EGLDisplay per (platform, native display) pair, so two
// Contexts on the same platform share a display. eglTerminate would destroy
// the other Context's resources too, so initialization is counted per display
// and only the last lease terminates it.
#pragma once

#include <EGL/egl.h>

namespace glc::detail {

class EglDisplayLease {
 public:
  // Initializes `display` unless another lease already did; throws GlError.
  explicit EglDisplayLease(EGLDisplay display);
  ~EglDisplayLease();
  EglDisplayLease(const EglDisplayLease&) = delete;
  EglDisplayLease& operator=(const EglDisplayLease&) = delete;

  EGLDisplay get() const noexcept { return display_; }
  EGLint major() const noexcept { return major_; }
  EGLint minor() const noexcept { return minor_; }

 private:
  EGLDisplay display_;
  EGLint major_ = 0;
  EGLint minor_ = 0;
};

}  // namespace glc::detail
