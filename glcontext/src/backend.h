// Internal: the window-system half of a Context (EGL or OSMesa). A Backend
// owns the native context and knows how to bind it and how to look up GL
// functions; everything GL-level lives in Context.
#pragma once

#include <memory>

namespace glc::detail {

class Backend {
 public:
  virtual ~Backend() = default;
  Backend() = default;
  Backend(const Backend&) = delete;
  Backend& operator=(const Backend&) = delete;

  // Makes this the context of the calling thread; throws GlError.
  //
  // EGL and OSMesa share Mesa's libglapi dispatch, yet neither API knows
  // about the other: after OSMesaMakeCurrent, EGL still believes its context
  // is current and turns a later eglMakeCurrent of it into a no-op, so GL
  // calls would keep going to the OSMesa context. We therefore track the
  // backend current on each thread and properly unbind it before binding a
  // different one, which keeps both APIs' view of "current" truthful.
  void make_current();
  // Unbinds this backend if it is current on the calling thread.
  void release_current() noexcept;

  // Address of a GL function, or nullptr.
  virtual void* get_proc(const char* name) const = 0;

 protected:
  // Native bind/unbind of this context on the calling thread. Derived
  // destructors must call release_current() before destroying the context.
  virtual void bind() = 0;
  virtual void unbind() noexcept = 0;
};

// Each factory returns a backend whose 3.3 core context is already current,
// or throws GlError with a short reason (the caller prefixes the platform).
// `allow_software`: whether Mesa's software (llvmpipe) EGL device may be used.
std::unique_ptr<Backend> create_egl_device_backend(bool allow_software);
std::unique_ptr<Backend> create_egl_surfaceless_backend();
std::unique_ptr<Backend> create_egl_default_backend();
std::unique_ptr<Backend> create_osmesa_backend();

}  // namespace glc::detail
