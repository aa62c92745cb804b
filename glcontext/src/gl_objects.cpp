// Deleters for every wrapper and the factories of the plain name-only ones.
#include "glcontext/error.h"
#include "glcontext/resources.h"

#include <algorithm>
#include <string>

namespace glc {
namespace detail {

void delete_shader(const GlApi& gl, GLuint id) { gl.glDeleteShader(id); }
void delete_program(const GlApi& gl, GLuint id) { gl.glDeleteProgram(id); }
void delete_texture(const GlApi& gl, GLuint id) { gl.glDeleteTextures(1, &id); }
void delete_framebuffer(const GlApi& gl, GLuint id) { gl.glDeleteFramebuffers(1, &id); }
void delete_buffer(const GlApi& gl, GLuint id) { gl.glDeleteBuffers(1, &id); }
void delete_vertex_array(const GlApi& gl, GLuint id) { gl.glDeleteVertexArrays(1, &id); }
void delete_query(const GlApi& gl, GLuint id) { gl.glDeleteQueries(1, &id); }
void delete_renderbuffer(const GlApi& gl, GLuint id) { gl.glDeleteRenderbuffers(1, &id); }

}  // namespace detail

namespace {

// glGen* never fails in practice, but a zero name (e.g. no current context)
// would make the wrapper silently own nothing; fail loudly instead.
GLuint checked_name(const GlApi& gl, GLuint id, const char* what) {
  check(gl, what);
  if (id == 0) throw GlError(std::string(what) + " returned 0 (is a context current?)");
  return id;
}

}  // namespace

Texture Texture::create(const GlApi& gl) {
  GLuint id = 0;
  gl.glGenTextures(1, &id);
  return Texture(gl, checked_name(gl, id, "glGenTextures"));
}

Renderbuffer Renderbuffer::create(const GlApi& gl, int width, int height, GLenum internal_format, int samples) {
  GLuint id = 0;
  gl.glGenRenderbuffers(1, &id);
  Renderbuffer rb(gl, checked_name(gl, id, "glGenRenderbuffers"));
  GLint max_samples = 0;
  gl.glGetIntegerv(GL_MAX_SAMPLES, &max_samples);
  rb.samples_ = samples > 0 ? std::min(samples, static_cast<int>(max_samples)) : 0;
  gl.glBindRenderbuffer(GL_RENDERBUFFER, id);
  if (rb.samples_ > 0)
    gl.glRenderbufferStorageMultisample(GL_RENDERBUFFER, rb.samples_, internal_format, width, height);
  else
    gl.glRenderbufferStorage(GL_RENDERBUFFER, internal_format, width, height);
  check(gl, "glRenderbufferStorage");
  return rb;
}

Framebuffer Framebuffer::create(const GlApi& gl) {
  GLuint id = 0;
  gl.glGenFramebuffers(1, &id);
  return Framebuffer(gl, checked_name(gl, id, "glGenFramebuffers"));
}

Buffer Buffer::create(const GlApi& gl) {
  GLuint id = 0;
  gl.glGenBuffers(1, &id);
  return Buffer(gl, checked_name(gl, id, "glGenBuffers"));
}

Buffer Buffer::create(const GlApi& gl, GLenum target, std::size_t bytes, const void* data, GLenum usage) {
  Buffer buffer = create(gl);
  gl.glBindBuffer(target, buffer.id());
  gl.glBufferData(target, static_cast<GLsizeiptr>(bytes), data, usage);
  check(gl, "glBufferData");
  return buffer;
}

VertexArray VertexArray::create(const GlApi& gl) {
  GLuint id = 0;
  gl.glGenVertexArrays(1, &id);
  return VertexArray(gl, checked_name(gl, id, "glGenVertexArrays"));
}

void VertexArray::bind() const { api()->glBindVertexArray(id()); }

Query Query::create(const GlApi& gl) {
  GLuint id = 0;
  gl.glGenQueries(1, &id);
  return Query(gl, checked_name(gl, id, "glGenQueries"));
}

}  // namespace glc
