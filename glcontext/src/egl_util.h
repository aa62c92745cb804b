// Internal: small EGL helpers shared by the EGL backend and platform code.
#pragma once

#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <string>

namespace glc::detail {

// "EGL_BAD_ALLOC" etc. for an eglGetError code.
std::string egl_error_name(EGLint error);

// "<call> failed (EGL_BAD_...)" using the thread's current eglGetError.
std::string egl_failure(const char* call);

// Whether the space-separated extension string `list` (may be null)
// contains exactly `name` (not merely a prefix of another extension).
bool has_extension(const char* list, const char* name);

// Client extensions (eglQueryString(EGL_NO_DISPLAY, ...)); empty if the EGL
// implementation predates EGL_EXT_client_extensions.
const char* client_extensions();

// eglGetProcAddress cast to the requested pointer type; nullptr if unknown.
template <class Fn>
Fn egl_proc(const char* name) {
  return reinterpret_cast<Fn>(eglGetProcAddress(name));
}

}  // namespace glc::detail
