// RAII, move-only owners of GL objects. Each holds a pointer to the GlApi of
// the Context it was created in and deletes its object in the destructor, so
// destroy resources before their Context (and with that context current).
#pragma once
#include <cstddef>

#include "glcontext/gl_api.h"

#include <initializer_list>
#include <span>
#include <string_view>
#include <utility>

namespace glc {
namespace detail {

void delete_shader(const GlApi& gl, GLuint id);
void delete_program(const GlApi& gl, GLuint id);
void delete_texture(const GlApi& gl, GLuint id);
void delete_framebuffer(const GlApi& gl, GLuint id);
void delete_buffer(const GlApi& gl, GLuint id);
void delete_vertex_array(const GlApi& gl, GLuint id);
void delete_query(const GlApi& gl, GLuint id);
void delete_renderbuffer(const GlApi& gl, GLuint id);

// Shared ownership mechanics: one GL name plus the API to delete it with.
// A default-constructed or moved-from object owns nothing (id() == 0).
template <void (*Delete)(const GlApi&, GLuint)>
class GlObject {
 public:
  GlObject() = default;
  ~GlObject() { reset(); }

  GlObject(const GlObject&) = delete;
  GlObject& operator=(const GlObject&) = delete;
  GlObject(GlObject&& other) noexcept : gl_(std::exchange(other.gl_, nullptr)), id_(std::exchange(other.id_, 0)) {}
  GlObject& operator=(GlObject&& other) noexcept {
    if (this != &other) {
      reset();
      gl_ = std::exchange(other.gl_, nullptr);
      id_ = std::exchange(other.id_, 0);
    }
    return *this;
  }

  GLuint id() const noexcept { return id_; }
  const GlApi* api() const noexcept { return gl_; }
  explicit operator bool() const noexcept { return id_ != 0; }

  // Deletes the object now; the wrapper then owns nothing.
  void reset() noexcept {
    if (id_ != 0 && gl_ != nullptr) Delete(*gl_, id_);
    id_ = 0;
  }

 protected:
  // Adopts `id`; only the wrappers' factories create objects.
  GlObject(const GlApi& gl, GLuint id) noexcept : gl_(&gl), id_(id) {}

 private:
  const GlApi* gl_ = nullptr;
  GLuint id_ = 0;
};

}  // namespace detail

class Shader : public detail::GlObject<&detail::delete_shader> {
 public:
  Shader() = default;
  // Compiles one stage (GL_VERTEX_SHADER, GL_FRAGMENT_SHADER, ...). On
  // failure throws GlError "shader '<label>' (<stage>) failed to compile:"
  // followed by the driver's full info log.
  static Shader compile(const GlApi& gl, GLenum stage, std::string_view source, std::string_view label);

 private:
  using GlObject::GlObject;
};

class Program : public detail::GlObject<&detail::delete_program> {
 public:
  Program() = default;
  // Compiles both stages and links them. Compile or link failures throw
  // GlError carrying `label` and the driver's full info log.
  static Program link(const GlApi& gl, std::string_view vertex_src, std::string_view fragment_src,
                      std::string_view label);
  // A vertex shader alone whose outputs `varyings` are captured by transform feedback, interleaved
  // in that order into one buffer (GL_INTERLEAVED_ATTRIBS); draw with GL_RASTERIZER_DISCARD.
  static Program link_capture(const GlApi& gl, std::string_view vertex_src, std::span<const char* const> varyings,
                              std::string_view label);

  // glGetUniformLocation; -1 when the uniform does not exist or was
  // optimized away (not an error, GL ignores glUniform* on -1).
  GLint uniform(const char* name) const;
  void use() const;

 private:
  using GlObject::GlObject;
  template <class BeforeLink>
  static Program link_stages(const GlApi& gl, std::initializer_list<const Shader*> stages, std::string_view label,
                             BeforeLink&& before_link);
};

class Texture : public detail::GlObject<&detail::delete_texture> {
 public:
  Texture() = default;
  // A bare texture name without storage.
  static Texture create(const GlApi& gl);
  // A GL_TEXTURE_2D with one level, NEAREST filtering and CLAMP_TO_EDGE.
  // `data` may be null (uninitialized storage); otherwise rows are tightly
  // packed (no row padding, whatever the format), first row = bottom (y=0).
  // Leaves the texture bound to GL_TEXTURE_2D on the active texture unit.
  static Texture create_2d(const GlApi& gl, int width, int height, GLenum internal_format, GLenum format, GLenum type,
                           const void* data);

  int width() const noexcept { return width_; }
  int height() const noexcept { return height_; }
  GLenum internal_format() const noexcept { return internal_format_; }

 private:
  using GlObject::GlObject;
  int width_ = 0;
  int height_ = 0;
  GLenum internal_format_ = 0;
};

class Renderbuffer : public detail::GlObject<&detail::delete_renderbuffer> {
 public:
  Renderbuffer() = default;
  // Storage of `internal_format` (GL_RGBA8, GL_DEPTH_COMPONENT24, ...), multisampled when samples
  // > 0 (clamped to GL_MAX_SAMPLES; samples() says how many the driver gave). Throws GlError.
  static Renderbuffer create(const GlApi& gl, int width, int height, GLenum internal_format, int samples = 0);
  int samples() const noexcept { return samples_; }

 private:
  using GlObject::GlObject;
  int samples_ = 0;
};

class Framebuffer : public detail::GlObject<&detail::delete_framebuffer> {
 public:
  Framebuffer() = default;
  static Framebuffer create(const GlApi& gl);

  // Binds to GL_FRAMEBUFFER (draw and read).
  void bind() const;
  // Attaches level 0 of a 2D texture at GL_COLOR_ATTACHMENT0 + index, makes
  // glDrawBuffers cover every attached slot, then checks completeness and
  // throws GlError with the status name. Leaves the framebuffer bound.
  void attach_color(const Texture& texture, int index = 0);
  // Attaches a renderbuffer at `attachment` (GL_COLOR_ATTACHMENT0, GL_DEPTH_ATTACHMENT, ...); with
  // `check_complete`, then checks completeness as attach_color does. Leaves the framebuffer bound.
  void attach(GLenum attachment, const Renderbuffer& renderbuffer, bool check_complete = true);

 private:
  using GlObject::GlObject;
  unsigned attached_mask_ = 0;  // bit i: GL_COLOR_ATTACHMENT0 + i in use
};

class Buffer : public detail::GlObject<&detail::delete_buffer> {
 public:
  Buffer() = default;
  static Buffer create(const GlApi& gl);
  // A buffer of `bytes` bytes (data may be null: uninitialised) with `usage` (GL_STATIC_DRAW, ...),
  // filled through `target`, which it is left bound to. Throws GlError on a GL error (out of memory).
  static Buffer create(const GlApi& gl, GLenum target, std::size_t bytes, const void* data, GLenum usage);

 private:
  using GlObject::GlObject;
};

// A byte offset into the buffer bound to a vertex attribute or element target, in the pointer form
// glVertexAttribPointer and glDrawElements take it.
inline const void* buffer_offset(std::size_t bytes) { return reinterpret_cast<const void*>(bytes); }

class VertexArray : public detail::GlObject<&detail::delete_vertex_array> {
 public:
  VertexArray() = default;
  static VertexArray create(const GlApi& gl);
  // A core profile needs some VAO bound for any draw, even attribute-less
  // full-screen passes driven by gl_VertexID.
  void bind() const;

 private:
  using GlObject::GlObject;
};

class Query : public detail::GlObject<&detail::delete_query> {
 public:
  Query() = default;
  static Query create(const GlApi& gl);

 private:
  using GlObject::GlObject;
};

}  // namespace glc
