#include "glcontext/error.h"

#include <cstdio>

namespace glc {
namespace {

std::string hex_code(const char* prefix, GLenum code) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%s 0x%04X", prefix, static_cast<unsigned>(code));
  return buf;
}

}  // namespace

std::string gl_error_name(GLenum error) {
  switch (error) {
    case GL_NO_ERROR:
      return "GL_NO_ERROR";
    case GL_INVALID_ENUM:
      return "GL_INVALID_ENUM";
    case GL_INVALID_VALUE:
      return "GL_INVALID_VALUE";
    case GL_INVALID_OPERATION:
      return "GL_INVALID_OPERATION";
    case GL_INVALID_FRAMEBUFFER_OPERATION:
      return "GL_INVALID_FRAMEBUFFER_OPERATION";
    case GL_OUT_OF_MEMORY:
      return "GL_OUT_OF_MEMORY";
    case GL_STACK_UNDERFLOW:
      return "GL_STACK_UNDERFLOW";
    case GL_STACK_OVERFLOW:
      return "GL_STACK_OVERFLOW";
    default:
      return hex_code("GL error", error);
  }
}

std::string framebuffer_status_name(GLenum status) {
  switch (status) {
    case GL_FRAMEBUFFER_COMPLETE:
      return "GL_FRAMEBUFFER_COMPLETE";
    case GL_FRAMEBUFFER_UNDEFINED:
      return "GL_FRAMEBUFFER_UNDEFINED";
    case GL_FRAMEBUFFER_INCOMPLETE_ATTACHMENT:
      return "GL_FRAMEBUFFER_INCOMPLETE_ATTACHMENT";
    case GL_FRAMEBUFFER_INCOMPLETE_MISSING_ATTACHMENT:
      return "GL_FRAMEBUFFER_INCOMPLETE_MISSING_ATTACHMENT";
    case GL_FRAMEBUFFER_INCOMPLETE_DRAW_BUFFER:
      return "GL_FRAMEBUFFER_INCOMPLETE_DRAW_BUFFER";
    case GL_FRAMEBUFFER_INCOMPLETE_READ_BUFFER:
      return "GL_FRAMEBUFFER_INCOMPLETE_READ_BUFFER";
    case GL_FRAMEBUFFER_UNSUPPORTED:
      return "GL_FRAMEBUFFER_UNSUPPORTED";
    case GL_FRAMEBUFFER_INCOMPLETE_MULTISAMPLE:
      return "GL_FRAMEBUFFER_INCOMPLETE_MULTISAMPLE";
    case GL_FRAMEBUFFER_INCOMPLETE_LAYER_TARGETS:
      return "GL_FRAMEBUFFER_INCOMPLETE_LAYER_TARGETS";
    // glCheckFramebufferStatus returns 0 when the call itself failed.
    case 0:
      return "glCheckFramebufferStatus failed (0)";
    default:
      return hex_code("framebuffer status", status);
  }
}

void check(const GlApi& gl, const char* what) {
  std::string names;
  // Bounded: each error flag is reported once, but a lost context may keep
  // returning an error forever (GL_CONTEXT_LOST in newer GL), so never spin.
  for (int i = 0; i < 16; ++i) {
    const GLenum err = gl.glGetError();
    if (err == GL_NO_ERROR) break;
    if (!names.empty()) names += ", ";
    names += gl_error_name(err);
  }
  if (!names.empty()) throw GlError(std::string(what) + ": " + names);
}

}  // namespace glc
