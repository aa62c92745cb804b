#include "glcontext/error.h"
#include "glcontext/resources.h"

namespace glc {

Texture Texture::create_2d(const GlApi& gl, int width, int height, GLenum internal_format, GLenum format, GLenum type,
                           const void* data) {
  Texture tex = create(gl);
  gl.glBindTexture(GL_TEXTURE_2D, tex.id());
  // Exact texel values matter (wavelet coefficients, glyph masks): no
  // filtering, no wrapping, and a single level so the texture is complete
  // without mipmaps.
  gl.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  gl.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  gl.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  gl.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  gl.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_BASE_LEVEL, 0);
  gl.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, 0);

  // The default unpack alignment of 4 would misread tightly packed rows of
  // e.g. odd-width R8 images; use 1 for this upload and restore the caller's.
  GLint old_alignment = 4;
  gl.glGetIntegerv(GL_UNPACK_ALIGNMENT, &old_alignment);
  gl.glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  gl.glTexImage2D(GL_TEXTURE_2D, 0, static_cast<GLint>(internal_format), width, height, 0, format, type, data);
  gl.glPixelStorei(GL_UNPACK_ALIGNMENT, old_alignment);
  check(gl, "Texture::create_2d (glTexImage2D)");

  tex.width_ = width;
  tex.height_ = height;
  tex.internal_format_ = internal_format;
  return tex;
}

}  // namespace glc
