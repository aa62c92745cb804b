// Shader compilation and program linking with full driver logs in errors.
#include "glcontext/error.h"
#include "glcontext/resources.h"

#include <initializer_list>
#include <string>

namespace glc {
namespace {

std::string stage_name(GLenum stage) {
  switch (stage) {
    case GL_VERTEX_SHADER:
      return "vertex";
    case GL_FRAGMENT_SHADER:
      return "fragment";
    case GL_GEOMETRY_SHADER:
      return "geometry";
    default:
      return "stage " + std::to_string(stage);
  }
}

std::string shader_log(const GlApi& gl, GLuint shader) {
  GLint length = 0;
  gl.glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &length);
  if (length <= 0) return "(no info log)";
  std::string log(static_cast<std::size_t>(length), '\0');
  gl.glGetShaderInfoLog(shader, length, &length, log.data());
  log.resize(static_cast<std::size_t>(length));
  return log;
}

std::string program_log(const GlApi& gl, GLuint program) {
  GLint length = 0;
  gl.glGetProgramiv(program, GL_INFO_LOG_LENGTH, &length);
  if (length <= 0) return "(no info log)";
  std::string log(static_cast<std::size_t>(length), '\0');
  gl.glGetProgramInfoLog(program, length, &length, log.data());
  log.resize(static_cast<std::size_t>(length));
  return log;
}

}  // namespace

Shader Shader::compile(const GlApi& gl, GLenum stage, std::string_view source, std::string_view label) {
  const GLuint id = gl.glCreateShader(stage);
  if (id == 0) {
    check(gl, "glCreateShader");
    throw GlError("glCreateShader returned 0 for '" + std::string(label) + "'");
  }
  Shader shader(gl, id);  // owns it from here, also on the throwing paths

  // Pass the length: string_view need not be NUL-terminated.
  const GLchar* text = source.data();
  const GLint length = static_cast<GLint>(source.size());
  gl.glShaderSource(id, 1, &text, &length);
  gl.glCompileShader(id);

  GLint ok = GL_FALSE;
  gl.glGetShaderiv(id, GL_COMPILE_STATUS, &ok);
  if (ok != GL_TRUE) {
    throw GlError("shader '" + std::string(label) + "' (" + stage_name(stage) + ") failed to compile:\n" +
                  shader_log(gl, id));
  }
  return shader;
}

// Links the compiled stages into a new program; `before_link` runs with the shaders attached (to
// name transform feedback varyings, say).
template <class BeforeLink>
Program Program::link_stages(const GlApi& gl, std::initializer_list<const Shader*> stages, std::string_view label,
                             BeforeLink&& before_link) {
  const GLuint id = gl.glCreateProgram();
  if (id == 0) {
    check(gl, "glCreateProgram");
    throw GlError("glCreateProgram returned 0 for '" + std::string(label) + "'");
  }
  Program program(gl, id);
  for (const Shader* s : stages) gl.glAttachShader(id, s->id());
  before_link(id);
  gl.glLinkProgram(id);
  // Detach so the shader objects are really freed when they go out of scope (attached shaders
  // are only flagged for deletion).
  for (const Shader* s : stages) gl.glDetachShader(id, s->id());
  GLint ok = GL_FALSE;
  gl.glGetProgramiv(id, GL_LINK_STATUS, &ok);
  if (ok != GL_TRUE) {
    throw GlError("program '" + std::string(label) + "' failed to link:\n" + program_log(gl, id));
  }
  check(gl, "Program::link");
  return program;
}

Program Program::link(const GlApi& gl, std::string_view vertex_src, std::string_view fragment_src,
                      std::string_view label) {
  const Shader vs = Shader::compile(gl, GL_VERTEX_SHADER, vertex_src, label);
  const Shader fs = Shader::compile(gl, GL_FRAGMENT_SHADER, fragment_src, label);
  return link_stages(gl, {&vs, &fs}, label, [](GLuint) {});
}

Program Program::link_capture(const GlApi& gl, std::string_view vertex_src, std::span<const char* const> varyings,
                              std::string_view label) {
  const Shader vs = Shader::compile(gl, GL_VERTEX_SHADER, vertex_src, label);
  return link_stages(gl, {&vs}, label, [&](GLuint id) {
    gl.glTransformFeedbackVaryings(id, static_cast<GLsizei>(varyings.size()), varyings.data(), GL_INTERLEAVED_ATTRIBS);
  });
}

GLint Program::uniform(const char* name) const { return api()->glGetUniformLocation(id(), name); }

void Program::use() const { api()->glUseProgram(id()); }

}  // namespace glc
