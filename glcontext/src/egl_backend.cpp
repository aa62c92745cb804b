#include "egl_backend.h"

#include "egl_util.h"
#include "glcontext/error.h"

#include <string>

namespace glc::detail {

EglBackend::EglBackend(EGLDisplay display) : display_(display) {
  try {
    create_context();
  } catch (...) {
    // The destructor does not run for a throwing constructor.
    release();
    throw;
  }
}

EglBackend::~EglBackend() { release(); }

void EglBackend::create_context() {
  const EGLDisplay dpy = display_.get();
  const char* extensions = eglQueryString(dpy, EGL_EXTENSIONS);
  const bool v15 = display_.major() > 1 || (display_.major() == 1 && display_.minor() >= 5);
  // Version and profile attributes need EGL 1.5 or EGL_KHR_create_context;
  // without them we would silently get a legacy 2.1/3.0 context.
  if (!v15 && !has_extension(extensions, "EGL_KHR_create_context")) {
    throw GlError("EGL " + std::to_string(display_.major()) + "." + std::to_string(display_.minor()) +
                  " without EGL_KHR_create_context cannot request a core profile");
  }
  const bool surfaceless = has_extension(extensions, "EGL_KHR_surfaceless_context");

  // eglBindAPI is per thread; desktop GL, not the GLES default.
  if (!eglBindAPI(EGL_OPENGL_API)) throw GlError(egl_failure("eglBindAPI(EGL_OPENGL_API)"));

  // EGL_SURFACE_TYPE 0 means "no surface requirement" (we never need one).
  const EGLint config_attribs[] = {
      EGL_RENDERABLE_TYPE,
      EGL_OPENGL_BIT,
      EGL_SURFACE_TYPE,
      surfaceless ? 0 : EGL_PBUFFER_BIT,
      EGL_RED_SIZE,
      8,
      EGL_GREEN_SIZE,
      8,
      EGL_BLUE_SIZE,
      8,
      EGL_NONE,
  };
  EGLConfig config = nullptr;
  EGLint count = 0;
  if (!eglChooseConfig(dpy, config_attribs, &config, 1, &count)) {
    throw GlError(egl_failure("eglChooseConfig"));
  }
  if (count == 0) {
    const char* apis = eglQueryString(dpy, EGL_CLIENT_APIS);
    throw GlError(std::string("no EGL config for desktop OpenGL (client APIs: ") + (apis ? apis : "?") + ")");
  }

  const EGLint context_attribs[] = {
      EGL_CONTEXT_MAJOR_VERSION,           3,        EGL_CONTEXT_MINOR_VERSION, 3, EGL_CONTEXT_OPENGL_PROFILE_MASK,
      EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE,
  };
  context_ = eglCreateContext(dpy, config, EGL_NO_CONTEXT, context_attribs);
  if (context_ == EGL_NO_CONTEXT) throw GlError(egl_failure("eglCreateContext(3.3 core)"));

  if (!surfaceless) {
    const EGLint pbuffer_attribs[] = {EGL_WIDTH, 1, EGL_HEIGHT, 1, EGL_NONE};
    surface_ = eglCreatePbufferSurface(dpy, config, pbuffer_attribs);
    if (surface_ == EGL_NO_SURFACE) throw GlError(egl_failure("eglCreatePbufferSurface"));
  }
  make_current();
}

void EglBackend::bind() {
  // eglBindAPI is per thread, and this may be a different thread.
  if (!eglBindAPI(EGL_OPENGL_API)) throw GlError(egl_failure("eglBindAPI(EGL_OPENGL_API)"));
  if (!eglMakeCurrent(display_.get(), surface_, surface_, context_)) {
    throw GlError(egl_failure("eglMakeCurrent"));
  }
}

void EglBackend::unbind() noexcept {
  eglBindAPI(EGL_OPENGL_API);
  eglMakeCurrent(display_.get(), EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
}

void* EglBackend::get_proc(const char* name) const { return reinterpret_cast<void*>(eglGetProcAddress(name)); }

void EglBackend::release() noexcept {
  const EGLDisplay dpy = display_.get();
  if (context_ != EGL_NO_CONTEXT) {
    // Unbinds only if current on this thread (another Context may be).
    release_current();
    eglDestroyContext(dpy, context_);
    context_ = EGL_NO_CONTEXT;
  }
  if (surface_ != EGL_NO_SURFACE) {
    eglDestroySurface(dpy, surface_);
    surface_ = EGL_NO_SURFACE;
  }
  // display_ (the lease) terminates the display when it is the last user.
}

}  // namespace glc::detail
