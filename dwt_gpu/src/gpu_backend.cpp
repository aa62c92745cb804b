#include "dwt_gpu/gpu_backend.h"

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstring>
#include <string>
#include <utility>

#include "dwt/error.h"
#include "dwt_gpu/address_table.h"
#include "band_shader.h"
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
  BandShader band_shader;
  glc::VertexArray quad;  // attribute-less: the vertex shader builds the quad from gl_VertexID
  // The two pixel buffers of section 4.4.2; their input/output roles swap after every pass.
  glc::Texture planes[2];
  glc::Framebuffer targets[2];
  glc::Texture table;
  // A second plane's coefficients, kept while the first is transformed (process_bands).
  glc::Texture held;
  glc::Framebuffer held_target;
  // The pixel buffer planes are uploaded through, and its size in bytes.
  glc::Buffer upload_buffer;
  std::size_t upload_bytes = 0;
};

GpuBackend::GpuBackend(glc::Platform platform, bool eager) : platform_(platform) {
  if (eager) ensure_ready();
}

GpuBackend::~GpuBackend() {
  // GL objects must be deleted while their context is current.
  if (state_ && state_->context) state_->context->make_current();
}

void GpuBackend::release_context() noexcept {
  if (state_ && state_->context) state_->context->release_current();
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
  state->band_shader = BandShader::build(gl);
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
  return "gpu fragment shaders (" + (state_ ? state_->context->renderer() : std::string("context not yet created")) +
         ")";
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
  begin(params, plane.width, plane.height);
  auto t0 = Clock::now();
  upload({plane.data, plane.width, plane.height, plane.stride});
  timings_.upload_ms = ms_since(t0);
  t0 = Clock::now();
  run_levels(params, inverse);
  timings_.compute_ms = ms_since(t0);
  t0 = Clock::now();
  download(plane);
  timings_.download_ms = ms_since(t0);
}

void GpuBackend::process_bands(dwt::PlaneSpan<float> first, dwt::PlaneSpan<const float> second,
                               const dwt::DwtParams& params, std::span<const dwt::BandOperation> ops) {
  const bool two_planes = second.data != nullptr;
  if (two_planes && (second.width != first.width || second.height != first.height))
    throw dwt::DwtError("the two planes combined in the wavelet domain differ in size: " + std::to_string(first.width) +
                        "x" + std::to_string(first.height) + " and " + std::to_string(second.width) + "x" +
                        std::to_string(second.height));
  begin(params, first.width, first.height);
  State& s = *state_;
  double upload_ms = 0, compute_ms = 0;
  if (two_planes) {
    // The second plane's coefficients move to the held buffer by swapping names, not by copying.
    auto t0 = Clock::now();
    upload(second);
    upload_ms += ms_since(t0);
    t0 = Clock::now();
    run_levels(params, false);
    std::swap(s.planes[0], s.held);
    std::swap(s.targets[0], s.held_target);
    compute_ms += ms_since(t0);
  }
  auto t0 = Clock::now();
  upload({first.data, first.width, first.height, first.stride});
  upload_ms += ms_since(t0);
  t0 = Clock::now();
  run_levels(params, false);
  run_band_pass(ops, two_planes);
  run_levels(params, true);
  compute_ms += ms_since(t0);
  t0 = Clock::now();
  download(first);
  timings_.upload_ms = upload_ms;
  timings_.compute_ms = compute_ms;
  timings_.download_ms = ms_since(t0);
}

void GpuBackend::begin(const dwt::DwtParams& params, int width, int height) {
  dwt::validate(params, width, height);
  if (!supports(params.kernel)) throw dwt::DwtError("the reversible 5/3 runs on the CPU backend only");
  const bool first_use = !state_;
  ensure_ready();
  if (!first_use) timings_.context_ms = timings_.compile_ms = 0;
  State& s = *state_;
  const glc::GlApi& gl = s.context->gl();
  const int limit = s.context->max_texture_size();
  // The address table is as wide as the longest row plus the kernel's reach on both sides.
  const int table_width = params.levels > 0 ? std::max(width, height) + 2 * dwt::Kernel::kMaxRadius : 1;
  if (width > limit || height > limit || table_width > limit)
    throw dwt::DwtError("a " + std::to_string(width) + "x" + std::to_string(height) +
                        " plane exceeds this GPU's texture limit of " + std::to_string(limit) + " (" +
                        s.context->renderer() + "); tile it or use the CPU backend");
  // Pixel buffers (reused while the size stays): the two of section 4.4.2, whose input/output roles
  // swap after every pass, and one that holds a second plane's coefficients while the first is
  // transformed (process_bands).
  auto make = [&](glc::Texture& texture, glc::Framebuffer& target) {
    texture = glc::Texture::create_2d(gl, width, height, GL_R32F, GL_RED, GL_FLOAT, nullptr);
    target = glc::Framebuffer::create(gl);
    target.attach_color(texture);
  };
  if (s.planes[0].width() != width || s.planes[0].height() != height) {
    for (int i = 0; i < 2; ++i) make(s.planes[i], s.targets[i]);
    s.held = {};
    s.held_target = {};
  }
  if (!s.held) make(s.held, s.held_target);
}

// Through a pixel buffer, mapped and filled here, from which the texture is then filled on the GPU's
// side. From client memory, NVIDIA's driver copied a float plane at 2.3 GB/s on an H200 (29 ms for a
// 4096x4096 plane; README, "On an NVIDIA H200").
void GpuBackend::upload(dwt::PlaneSpan<const float> plane) {
  State& s = *state_;
  const glc::GlApi& gl = s.context->gl();
  const std::size_t row_bytes = static_cast<std::size_t>(plane.width) * sizeof(float);
  const std::size_t bytes = row_bytes * static_cast<std::size_t>(plane.height);
  if (!s.upload_buffer || s.upload_bytes < bytes) {
    s.upload_buffer = glc::Buffer::create(gl, GL_PIXEL_UNPACK_BUFFER, bytes, nullptr, GL_STREAM_DRAW);
    s.upload_bytes = bytes;
  }
  gl.glBindBuffer(GL_PIXEL_UNPACK_BUFFER, s.upload_buffer.id());
  void* mapped = gl.glMapBufferRange(GL_PIXEL_UNPACK_BUFFER, 0, static_cast<GLsizeiptr>(bytes),
                                     GL_MAP_WRITE_BIT | GL_MAP_INVALIDATE_BUFFER_BIT);
  if (mapped == nullptr) {
    gl.glBindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
    glc::check(gl, "mapping the upload buffer");
    throw glc::GlError("mapping the upload buffer gave no memory");
  }
  auto* out = static_cast<std::uint8_t*>(mapped);
  for (int y = 0; y < plane.height; ++y)
    std::memcpy(out + static_cast<std::size_t>(y) * row_bytes,
                plane.data + static_cast<std::ptrdiff_t>(y) * plane.stride, row_bytes);
  // False only where the buffer's contents were lost meanwhile (a display mode change): upload again.
  const bool intact = gl.glUnmapBuffer(GL_PIXEL_UNPACK_BUFFER) == GL_TRUE;
  gl.glActiveTexture(GL_TEXTURE0);
  gl.glBindTexture(GL_TEXTURE_2D, s.planes[0].id());
  gl.glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  if (intact) {
    gl.glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, plane.width, plane.height, GL_RED, GL_FLOAT, nullptr);
    gl.glBindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
  } else {
    gl.glBindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
    gl.glPixelStorei(GL_UNPACK_ROW_LENGTH, static_cast<GLint>(plane.stride));
    gl.glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, plane.width, plane.height, GL_RED, GL_FLOAT, plane.data);
    gl.glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
  }
  glc::check(gl, "uploading the plane");
  gl.glFinish();
}

void GpuBackend::run_levels(const dwt::DwtParams& params, bool inverse) {
  State& s = *state_;
  const glc::GlApi& gl = s.context->gl();
  const dwt::Kernel& kernel = dwt::get_kernel(params.kernel);
  const auto levels = dwt::decomposition(s.planes[0].width(), s.planes[0].height(), params.origin, params.levels);
  const AddressTable table = build_table(levels, dwt::Kernel::kMaxRadius, params.boundary, inverse);
  s.table = glc::Texture::create_2d(gl, table.width, table.rows, GL_RGBA32F, GL_RGBA, GL_FLOAT, table.rgba.data());

  // Per level a horizontal then a vertical pass over the current region, each a quad.
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
}

void GpuBackend::run_band_pass(std::span<const dwt::BandOperation> ops, bool reads_second) {
  State& s = *state_;
  const glc::GlApi& gl = s.context->gl();
  const int W = s.planes[0].width(), H = s.planes[0].height();
  s.band_shader.program.use();
  gl.glUniform1i(s.band_shader.first, 0);
  gl.glUniform1i(s.band_shader.second, 2);
  gl.glActiveTexture(GL_TEXTURE0);
  gl.glBindTexture(GL_TEXTURE_2D, s.planes[0].id());
  gl.glActiveTexture(GL_TEXTURE2);
  gl.glBindTexture(GL_TEXTURE_2D, s.held.id());
  s.targets[1].bind();
  s.quad.bind();
  auto draw = [&](const dwt::LayoutRect& r, dwt::BandRule rule, float first_factor, float second_factor) {
    if (r.width <= 0 || r.height <= 0) return;
    gl.glViewport(r.x, r.y, r.width, r.height);
    gl.glUniform1i(s.band_shader.rule, static_cast<GLint>(rule));
    gl.glUniform1f(s.band_shader.first_factor, first_factor);
    gl.glUniform1f(s.band_shader.second_factor, second_factor);
    gl.glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
  };
  long long covered = 0;
  for (const dwt::BandOperation& op : ops) {
    const dwt::LayoutRect& r = op.rect;
    if (r.x < 0 || r.y < 0 || r.x + r.width > W || r.y + r.height > H)
      throw dwt::DwtError("band rectangle outside the plane");
    if (op.rule != dwt::BandRule::First && !reads_second)
      throw dwt::DwtError("a band rule that combines two planes needs a second plane of the same size");
    covered += static_cast<long long>(r.width) * r.height;
  }
  // Samples no operation covers are kept, as on the CPU: one copying quad over the plane first.
  if (covered < static_cast<long long>(W) * H) draw({0, 0, W, H}, dwt::BandRule::First, 1.0f, 1.0f);
  for (const dwt::BandOperation& op : ops) draw(op.rect, op.rule, op.first_factor, op.second_factor);
  glc::check(gl, "running the band operation pass");
  // The result becomes buffer 0, where the inverse transform starts.
  std::swap(s.planes[0], s.planes[1]);
  std::swap(s.targets[0], s.targets[1]);
  gl.glFinish();
}

void GpuBackend::download(dwt::PlaneSpan<float> plane) {
  State& s = *state_;
  const glc::GlApi& gl = s.context->gl();
  s.targets[0].bind();
  gl.glReadBuffer(GL_COLOR_ATTACHMENT0);
  gl.glPixelStorei(GL_PACK_ALIGNMENT, 4);
  gl.glPixelStorei(GL_PACK_ROW_LENGTH, static_cast<GLint>(plane.stride));
  gl.glReadPixels(0, 0, plane.width, plane.height, GL_RED, GL_FLOAT, plane.data);
  gl.glPixelStorei(GL_PACK_ROW_LENGTH, 0);
  glc::check(gl, "reading the plane back");
}

}  // namespace dwt_gpu
