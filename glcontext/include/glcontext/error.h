// Error type of the glcontext layer and the glGetError check helper.
#pragma once

#include "glcontext/gl_api.h"

#include <stdexcept>
#include <string>
#include <string_view>

namespace glc {

// Every failure in this library (context creation, missing functions, GL
// errors, shader compile/link logs, incomplete framebuffers) is a GlError, so
// callers can catch one type and print what().
class GlError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// "GL_INVALID_OPERATION" etc.; unknown codes come back as "GL error 0x...".
std::string gl_error_name(GLenum error);

// "GL_FRAMEBUFFER_INCOMPLETE_ATTACHMENT" etc. for glCheckFramebufferStatus.
std::string framebuffer_status_name(GLenum status);

// Drains glGetError and throws GlError("<what>: GL_INVALID_OPERATION") when
// any error was pending (several flags are joined with ", "). Draining all
// flags keeps a stale error from being blamed on the next checked call.
void check(const GlApi& gl, const char* what);

}  // namespace glc
