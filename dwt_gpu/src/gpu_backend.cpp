#include "dwt_gpu/gpu_backend.h"

#include <chrono>
#include <string>
#include <utility>

#include "dwt/error.h"
#include "dwt_gpu/address_table.h"
#include "dwt_shader.h"
#include "glcontext/error.h"
#include "glcontext/resources.h"

namespace dwt_gpu {
namespace {

using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

}  // namespace

struct GpuBackend::State {
  std::unique_ptr<glc::Context> context;
  DwtShader shader;
  glc::VertexArray quad;  // attribute-less: the vertex shader builds the quad from gl_VertexID
  // The two pixel buffers of section 4.4.2; their input/output roles swap after every pass.
  glc::Texture planes[2];
  glc::Framebuffer targets[2];
  glc::Texture table;
};

GpuBackend::GpuBackend(glc::Platform platform, bool eager) : platform_(platform) {
  if (eager) ensure_ready();
}

GpuBackend::~GpuBackend() {
  // GL objects must be deleted while their context is current.
  if (state_ && state_->context) state_->context->make_current();
}

void GpuBackend::ensure_ready() {
  if (state_) {
    state_->context->make_current();
    return;
  }
  const auto t0 = Clock::now();
  auto context = glc::Context::create(platform_ == glc::Platform::Auto ? glc::platform_from_env() : platform_);
  timings_.context_ms = ms_since(t0);
  prepare(std::move(context));
}

GpuBackend::GpuBackend(std::unique_ptr<glc::Context> context) : platform_(context->platform()) {
  context->make_current();
  prepare(std::move(context));
}

void GpuBackend::prepare(std::unique_ptr<glc::Context> context) {
  auto state = std::make_unique<State>();
  state->context = std::move(context);
  const auto t0 = Clock::now();
  const glc::GlApi& gl = state->context->gl();
  state->shader = DwtShader::build(gl);
  state->quad = glc::VertexArray::create(gl);
  gl.glFinish();
  timings_.compile_ms = ms_since(t0);
  state_ = std::move(state);
}

std::string GpuBackend::renderer() {
  ensure_ready();
  return state_->context->description();
}

std::string GpuBackend::name() const {
  return "gpu fragment shaders (" + (state_ ? state_->context->renderer() : std::string("context not yet created")) + ")";
}

bool GpuBackend::supports(dwt::KernelId kernel) const { return !dwt::get_kernel(kernel).reversible; }

void GpuBackend::forward(dwt::PlaneSpan<float> plane, const dwt::DwtParams& params) { transform(plane, params, false); }
void GpuBackend::inverse(dwt::PlaneSpan<float> plane, const dwt::DwtParams& params) { transform(plane, params, true); }

void GpuBackend::forward(dwt::PlaneSpan<std::int32_t>, const dwt::DwtParams&) {
  throw dwt::DwtError("the reversible 5/3 runs on the CPU backend only");
}
void GpuBackend::inverse(dwt::PlaneSpan<std::int32_t>, const dwt::DwtParams&) {
  throw dwt::DwtError("the reversible 5/3 runs on the CPU backend only");
}

void GpuBackend::transform(dwt::PlaneSpan<float> plane, const dwt::DwtParams& params, bool inverse) {
  dwt::validate(params, plane.width, plane.height);
  const dwt::Kernel& kernel = dwt::get_kernel(params.kernel);
  if (!supports(params.kernel)) throw dwt::DwtError("the reversible 5/3 runs on the CPU backend only");

  const bool first_use = !state_;
  ensure_ready();
  if (!first_use) timings_.context_ms = timings_.compile_ms = 0;
  State& s = *state_;
  const glc::GlApi& gl = s.context->gl();
  const int W = plane.width, H = plane.height;

  const auto levels = dwt::decomposition(W, H, params.origin, params.levels);
  const AddressTable table = build_table(levels, dwt::Kernel::kMaxRadius, params.boundary, inverse);
  const int limit = s.context->max_texture_size();
  if (W > limit || H > limit || table.width > limit)
    throw dwt::DwtError("a " + std::to_string(W) + "x" + std::to_string(H) + " plane exceeds this GPU's texture limit of " +
                        std::to_string(limit) + " (" + s.context->renderer() + "); tile it or use the CPU backend");

  // Upload: pixel buffers (reused while the size stays), the address table, the plane.
  auto t0 = Clock::now();
  if (s.planes[0].width() != W || s.planes[0].height() != H) {
    for (int i = 0; i < 2; ++i) {
      s.planes[i] = glc::Texture::create_2d(gl, W, H, GL_R32F, GL_RED, GL_FLOAT, nullptr);
      s.targets[i] = glc::Framebuffer::create(gl);
      s.targets[i].attach_color(s.planes[i]);
    }
  }
  s.table = glc::Texture::create_2d(gl, table.width, table.rows, GL_RGBA32F, GL_RGBA, GL_FLOAT, table.rgba.data());
  gl.glBindTexture(GL_TEXTURE_2D, s.planes[0].id());
  gl.glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  gl.glPixelStorei(GL_UNPACK_ROW_LENGTH, static_cast<GLint>(plane.stride));
  gl.glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, W, H, GL_RED, GL_FLOAT, plane.data);
  gl.glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
  glc::check(gl, "uploading the plane");
  gl.glFinish();
  timings_.upload_ms = ms_since(t0);

  // Compute: per level a horizontal then a vertical pass over the current region, each a quad.
  t0 = Clock::now();
  const KernelBank bank = kernel_bank(kernel, inverse);
  s.shader.program.use();
  gl.glUniform1i(s.shader.source, 0);
  gl.glUniform1i(s.shader.table, 1);
  gl.glUniform1i(s.shader.pad, table.pad);
  gl.glUniform1i(s.shader.radius, inverse ? kernel.synthesis_radius : kernel.analysis_radius);
  gl.glUniform1fv(s.shader.taps, static_cast<GLsizei>(bank.size()), bank.data());
  gl.glActiveTexture(GL_TEXTURE1);
  gl.glBindTexture(GL_TEXTURE_2D, s.table.id());
  s.quad.bind();
  gl.glDisable(GL_DEPTH_TEST);
  gl.glDisable(GL_BLEND);

  int current = 0;  // which pixel buffer holds the latest data
  auto pass = [&](int level_index, const dwt::LevelGeometry& g, bool vertical) {
    gl.glActiveTexture(GL_TEXTURE0);
    gl.glBindTexture(GL_TEXTURE_2D, s.planes[current].id());
    s.targets[1 - current].bind();
    gl.glViewport(0, 0, g.x.length, g.y.length);
    gl.glUniform1i(s.shader.row, AddressTable::row_of(level_index, vertical));
    gl.glUniform1i(s.shader.vertical, vertical ? 1 : 0);
    gl.glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
    current = 1 - current;
  };
  // Two passes per level bring the data back to buffer 0 after every level, so buffer 0 always
  // holds the finished bands outside the region still being worked on.
  const int count = static_cast<int>(levels.size());
  for (int i = 0; i < count; ++i) {
    const int d = inverse ? count - 1 - i : i;
    const auto& g = levels[static_cast<std::size_t>(d)];
    if (g.x.length == 0 || g.y.length == 0) continue;
    pass(d, g, false);
    pass(d, g, true);
  }
  glc::check(gl, "running the DWT passes");
  gl.glFinish();
  timings_.compute_ms = ms_since(t0);

  // Download from buffer 0.
  t0 = Clock::now();
  s.targets[0].bind();
  gl.glReadBuffer(GL_COLOR_ATTACHMENT0);
  gl.glPixelStorei(GL_PACK_ALIGNMENT, 4);
  gl.glPixelStorei(GL_PACK_ROW_LENGTH, static_cast<GLint>(plane.stride));
  gl.glReadPixels(0, 0, W, H, GL_RED, GL_FLOAT, plane.data);
  gl.glPixelStorei(GL_PACK_ROW_LENGTH, 0);
  glc::check(gl, "reading the plane back");
  timings_.download_ms = ms_since(t0);
}

}  // namespace dwt_gpu
