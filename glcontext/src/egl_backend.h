// Internal: a desktop-GL 3.3 core EGL context on an already obtained display.
#pragma once

#include "backend.h"
#include "egl_display.h"

#include <EGL/egl.h>

namespace glc::detail {

class EglBackend final : public Backend {
 public:
  // Initializes `display`, creates the context and makes it current.
  // Throws GlError with the reason (the EGL call and error name).
  explicit EglBackend(EGLDisplay display);
  ~EglBackend() override;

  void* get_proc(const char* name) const override;

 protected:
  void bind() override;
  void unbind() noexcept override;

 private:
  void create_context();
  void release() noexcept;

  EglDisplayLease display_;
  EGLContext context_ = EGL_NO_CONTEXT;
  // A 1x1 pbuffer, only when the display lacks EGL_KHR_surfaceless_context
  // (we always render into FBOs, so the surface is never drawn to).
  EGLSurface surface_ = EGL_NO_SURFACE;
};

}  // namespace glc::detail
