#include "glcontext/error.h"
#include "glcontext/resources.h"

#include <string>

namespace glc {
namespace {

// GL guarantees at least 8 color attachments; more is never needed here.
constexpr int kMaxColorAttachments = 8;

}  // namespace

void Framebuffer::bind() const { api()->glBindFramebuffer(GL_FRAMEBUFFER, id()); }

void Framebuffer::attach_color(const Texture& texture, int index) {
  if (index < 0 || index >= kMaxColorAttachments) {
    throw GlError("Framebuffer::attach_color: index " + std::to_string(index) + " out of range");
  }
  const GlApi& gl = *api();
  bind();
  gl.glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0 + static_cast<GLenum>(index), GL_TEXTURE_2D,
                            texture.id(), 0);
  attached_mask_ |= 1u << index;

  // GL 3.3 calls a framebuffer incomplete when a draw buffer names an empty
  // attachment, so list exactly the attached slots and GL_NONE for gaps.
  GLenum buffers[kMaxColorAttachments];
  GLsizei count = 0;
  for (int i = 0; i < kMaxColorAttachments; ++i) {
    if ((attached_mask_ >> i) == 0) break;
    buffers[count++] = (attached_mask_ & (1u << i)) ? GL_COLOR_ATTACHMENT0 + static_cast<GLenum>(i) : GL_NONE;
  }
  gl.glDrawBuffers(count, buffers);
  // Likewise the read buffer must name an attachment: use the lowest one.
  int lowest = 0;
  while ((attached_mask_ & (1u << lowest)) == 0) ++lowest;
  gl.glReadBuffer(GL_COLOR_ATTACHMENT0 + static_cast<GLenum>(lowest));
  check(gl, "Framebuffer::attach_color");

  const GLenum status = gl.glCheckFramebufferStatus(GL_FRAMEBUFFER);
  if (status != GL_FRAMEBUFFER_COMPLETE) {
    throw GlError("framebuffer incomplete: " + framebuffer_status_name(status));
  }
}

void Framebuffer::attach(GLenum attachment, const Renderbuffer& renderbuffer, bool check_complete) {
  const GlApi& gl = *api();
  bind();
  gl.glFramebufferRenderbuffer(GL_FRAMEBUFFER, attachment, GL_RENDERBUFFER, renderbuffer.id());
  check(gl, "Framebuffer::attach");
  if (!check_complete) return;
  const GLenum status = gl.glCheckFramebufferStatus(GL_FRAMEBUFFER);
  if (status != GL_FRAMEBUFFER_COMPLETE) {
    throw GlError("framebuffer incomplete: " + framebuffer_status_name(status));
  }
}

}  // namespace glc
