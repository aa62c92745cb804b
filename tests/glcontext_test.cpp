// Tests for the headless GL context layer. They need a working EGL or OSMesa
// (Mesa llvmpipe is enough); platform-specific cases skip when unavailable.
#include "glcontext/context.h"
#include "glcontext/error.h"
#include "glcontext/gpu_fingerprint.h"
#include "glcontext/resources.h"

#include <gtest/gtest.h>

#include "support/scratch_dir.h"

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <vector>

namespace {

using glc::Context;
using glc::GlError;
using glc::Platform;

// Full-screen triangle from gl_VertexID alone: (-1,-1), (3,-1), (-1,3).
constexpr const char* kFullScreenVs = R"(#version 330 core
void main() {
  vec2 p = vec2(float((gl_VertexID & 1) << 2) - 1.0, float((gl_VertexID & 2) << 1) - 1.0);
  gl_Position = vec4(p, 0.0, 1.0);
}
)";

// Contexts for explicit platforms; nullptr (and the reason) when the platform
// cannot work on this machine, so the caller can GTEST_SKIP.
std::unique_ptr<Context> try_create(Platform platform, std::string* why) {
  try {
    return Context::create(platform);
  } catch (const GlError& e) {
    *why = e.what();
    return nullptr;
  }
}

// Renders a full-screen pass of `fragment_src` into a fresh R32F target of
// w x h and reads it back row by row, bottom row first.
std::vector<float> render_r32f(const Context& ctx, const char* fragment_src, int w, int h,
                               const glc::Texture* input = nullptr) {
  const glc::GlApi& gl = ctx.gl();
  const glc::Program program = glc::Program::link(gl, kFullScreenVs, fragment_src, "r32f-test");
  const glc::Texture target = glc::Texture::create_2d(gl, w, h, GL_R32F, GL_RED, GL_FLOAT, nullptr);
  glc::Framebuffer fbo = glc::Framebuffer::create(gl);
  fbo.attach_color(target);
  const glc::VertexArray vao = glc::VertexArray::create(gl);

  // Sentinel so a texel the draw missed is obvious.
  const float sentinel[4] = {-1.0f, 0.0f, 0.0f, 0.0f};
  gl.glClearBufferfv(GL_COLOR, 0, sentinel);
  gl.glViewport(0, 0, w, h);
  program.use();
  if (input != nullptr) {
    gl.glActiveTexture(GL_TEXTURE0);
    gl.glBindTexture(GL_TEXTURE_2D, input->id());
    gl.glUniform1i(program.uniform("src"), 0);
  }
  vao.bind();
  gl.glDrawArrays(GL_TRIANGLES, 0, 3);
  glc::check(gl, "full-screen draw");

  std::vector<float> pixels(static_cast<std::size_t>(w) * h, -2.0f);
  gl.glPixelStorei(GL_PACK_ALIGNMENT, 4);
  gl.glReadPixels(0, 0, w, h, GL_RED, GL_FLOAT, pixels.data());
  glc::check(gl, "glReadPixels");
  gl.glBindFramebuffer(GL_FRAMEBUFFER, 0);
  gl.glUseProgram(0);
  return pixels;
}

// Quick proof that a context really renders (used on every platform).
void expect_renders(const Context& ctx) {
  const std::vector<float> px = render_r32f(ctx, R"(#version 330 core
layout(location = 0) out float v;
void main() { v = 42.0; }
)",
                                            3, 2);
  for (float v : px) EXPECT_EQ(v, 42.0f);
}

// Sets an environment variable for one scope and restores the old value.
class ScopedEnv {
 public:
  ScopedEnv(const char* name, const char* value) : name_(name) {
    if (const char* old = std::getenv(name)) old_ = old;
    if (value) {
      setenv(name, value, 1);
    } else {
      unsetenv(name);
    }
  }
  ~ScopedEnv() {
    if (old_) {
      setenv(name_, old_->c_str(), 1);
    } else {
      unsetenv(name_);
    }
  }
  ScopedEnv(const ScopedEnv&) = delete;
  ScopedEnv& operator=(const ScopedEnv&) = delete;

 private:
  const char* name_;
  std::optional<std::string> old_;
};

TEST(GlContext, AutoCreates) {
  auto ctx = Context::create();
  ASSERT_NE(ctx, nullptr);
  std::cout << "[ auto     ] " << ctx->description() << " (vendor " << ctx->vendor() << ")\n";
  EXPECT_FALSE(ctx->renderer().empty());
  EXPECT_FALSE(ctx->version().empty());
  EXPECT_NE(ctx->platform(), Platform::Auto);
  EXPECT_GE(ctx->max_texture_size(), 1024);
  EXPECT_NE(ctx->description().find(std::string(glc::platform_name(ctx->platform()))), std::string::npos);
  expect_renders(*ctx);
}

TEST(GlContext, CreateDestroyRepeatedly) {
  for (int i = 0; i < 5; ++i) {
    auto ctx = Context::create();
    ASSERT_FALSE(ctx->renderer().empty()) << "iteration " << i;
    expect_renders(*ctx);
  }
}

TEST(GlContext, EglSurfaceless) {
  std::string why;
  auto ctx = try_create(Platform::EglSurfaceless, &why);
  // Only a machine whose EGL has no Mesa vendor (NVIDIA-only) lacks it.
  if (!ctx && why.find("not supported") != std::string::npos) GTEST_SKIP() << why;
  ASSERT_NE(ctx, nullptr) << why;
  std::cout << "[ surfless ] " << ctx->description() << "\n";
  EXPECT_EQ(ctx->platform(), Platform::EglSurfaceless);
  expect_renders(*ctx);
}

TEST(GlContext, OsMesa) {
  std::string why;
  auto ctx = try_create(Platform::OsMesa, &why);
  if (!ctx && why.find("not found") != std::string::npos) GTEST_SKIP() << why;
  ASSERT_NE(ctx, nullptr) << why;
  std::cout << "[ osmesa   ] " << ctx->description() << "\n";
  EXPECT_EQ(ctx->platform(), Platform::OsMesa);
  expect_renders(*ctx);
}

// These two depend on the machine (GPU present, X/Wayland default); report
// rather than require.
TEST(GlContext, EglDeviceIfAvailable) {
  std::string why;
  auto ctx = try_create(Platform::EglDevice, &why);
  if (!ctx) GTEST_SKIP() << why;
  std::cout << "[ device   ] " << ctx->description() << "\n";
  expect_renders(*ctx);
}

TEST(GlContext, EglDefaultIfAvailable) {
  std::string why;
  auto ctx = try_create(Platform::EglDefault, &why);
  if (!ctx) GTEST_SKIP() << why;
  std::cout << "[ default  ] " << ctx->description() << "\n";
  expect_renders(*ctx);
}

// Two contexts on one EGL display: destroying the first must not terminate
// the display under the second.
TEST(GlContext, TwoContextsShareADisplay) {
  auto a = Context::create();
  auto b = Context::create(a->platform());
  a->make_current();
  expect_renders(*a);
  a.reset();
  b->make_current();
  expect_renders(*b);
}

constexpr const char* kFetchTimesTwoFs = R"(#version 330 core
uniform sampler2D src;
layout(location = 0) out float v;
void main() { v = 2.0 * texelFetch(src, ivec2(gl_FragCoord.xy), 0).r; }
)";

// A 1x1 R32F texture holding `value`, in the current context.
glc::Texture single_texel(const Context& ctx, float value) {
  return glc::Texture::create_2d(ctx.gl(), 1, 1, GL_R32F, GL_RED, GL_FLOAT, &value);
}

float clear_red(const Context& ctx) {
  float rgba[4] = {};
  ctx.gl().glGetFloatv(GL_COLOR_CLEAR_VALUE, rgba);
  return rgba[0];
}

// EGL and OSMesa contexts alive together, switched back and forth. Both
// dispatch through Mesa's shared libglapi, so a switch that one API misses
// would send GL calls to the other context; per-context state (the clear
// color) and per-context textures show which context really answers.
TEST(GlContext, EglAndOsMesaInterleaved) {
  auto egl = Context::create();
  if (egl->platform() == Platform::OsMesa) GTEST_SKIP() << "no EGL platform works here";
  egl->gl().glClearColor(0.5f, 0.0f, 0.0f, 0.0f);
  glc::Texture egl_tex = single_texel(*egl, 7.0f);
  std::string why;
  auto osmesa = try_create(Platform::OsMesa, &why);  // now current
  if (!osmesa) GTEST_SKIP() << why;
  osmesa->gl().glClearColor(0.25f, 0.0f, 0.0f, 0.0f);
  glc::Texture osmesa_tex = single_texel(*osmesa, 9.0f);

  for (int i = 0; i < 3; ++i) {
    egl->make_current();
    EXPECT_EQ(clear_red(*egl), 0.5f) << i;
    EXPECT_EQ(render_r32f(*egl, kFetchTimesTwoFs, 1, 1, &egl_tex)[0], 14.0f) << i;
    osmesa->make_current();
    EXPECT_EQ(clear_red(*osmesa), 0.25f) << i;
    EXPECT_EQ(render_r32f(*osmesa, kFetchTimesTwoFs, 1, 1, &osmesa_tex)[0], 18.0f) << i;
  }
  // Resources are deleted through whichever context is current: their own.
  osmesa_tex.reset();
  egl->make_current();
  egl_tex.reset();
  // Destroying the non-current OSMesa context must leave the EGL one bound.
  osmesa.reset();
  EXPECT_EQ(clear_red(*egl), 0.5f);
}

// A context released on one thread can be used on another, and back.
TEST(GlContext, HandOverToAnotherThread) {
  auto ctx = Context::create();
  glc::Texture tex = single_texel(*ctx, 5.0f);
  ctx->release_current();
  float seen = 0.0f;
  std::string error;
  std::thread worker([&] {
    try {
      ctx->make_current();
      seen = render_r32f(*ctx, kFetchTimesTwoFs, 1, 1, &tex)[0];
      ctx->release_current();
    } catch (const GlError& e) {
      error = e.what();
    }
  });
  worker.join();
  EXPECT_EQ(error, "");
  EXPECT_EQ(seen, 10.0f);
  ctx->make_current();
  EXPECT_EQ(render_r32f(*ctx, kFetchTimesTwoFs, 1, 1, &tex)[0], 10.0f);
}

TEST(Platform, ParseRoundTrip) {
  for (Platform p :
       {Platform::Auto, Platform::EglDevice, Platform::EglSurfaceless, Platform::EglDefault, Platform::OsMesa}) {
    EXPECT_EQ(glc::parse_platform(glc::platform_name(p)), p);
  }
}

TEST(Platform, ParseRejectsUnknownAndListsValidNames) {
  try {
    glc::parse_platform("foo");
    FAIL() << "expected GlError";
  } catch (const GlError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("foo"), std::string::npos) << msg;
    for (const char* name : {"auto", "egl-device", "egl-surfaceless", "egl-default", "osmesa"}) {
      EXPECT_NE(msg.find(name), std::string::npos) << msg;
    }
  }
}

TEST(Platform, FromEnv) {
  {
    ScopedEnv env("GPUJ2K_GL", nullptr);
    EXPECT_EQ(glc::platform_from_env(), Platform::Auto);
  }
  {
    ScopedEnv env("GPUJ2K_GL", "");
    EXPECT_EQ(glc::platform_from_env(), Platform::Auto);
  }
  {
    ScopedEnv env("GPUJ2K_GL", "osmesa");
    EXPECT_EQ(glc::platform_from_env(), Platform::OsMesa);
  }
  {
    ScopedEnv env("GPUJ2K_GL", "foo");
    EXPECT_THROW(glc::platform_from_env(), GlError);
    try {
      glc::platform_from_env();
    } catch (const GlError& e) {
      EXPECT_NE(std::string(e.what()).find("GPUJ2K_GL"), std::string::npos) << e.what();
    }
  }
}

TEST(GlApi, MissingFunctionIsNamed) {
  auto ctx = Context::create();
  glc::GlApi api;
  const glc::GlApi& real = ctx->gl();
  // Pretend the driver lacks glFenceSync; everything else resolves.
  auto loader = [&real](const char* name) -> void* {
    if (std::string(name) == "glFenceSync") return nullptr;
    return reinterpret_cast<void*>(real.glGetString);  // any non-null address
  };
  try {
    glc::load(api, loader);
    FAIL() << "expected GlError";
  } catch (const GlError& e) {
    EXPECT_NE(std::string(e.what()).find("glFenceSync"), std::string::npos) << e.what();
  }
  EXPECT_EQ(api.glGetString, nullptr) << "failed load must leave the table untouched";
}

TEST(GlError, CheckNamesCallAndError) {
  auto ctx = Context::create();
  const glc::GlApi& gl = ctx->gl();
  glc::check(gl, "clean state");
  gl.glEnable(0xFFFF);  // not a capability -> GL_INVALID_ENUM
  try {
    glc::check(gl, "glEnable(bogus)");
    FAIL() << "expected GlError";
  } catch (const GlError& e) {
    EXPECT_STREQ(e.what(), "glEnable(bogus): GL_INVALID_ENUM");
  }
  EXPECT_NO_THROW(glc::check(gl, "after drain"));
}

TEST(Program, BrokenFragmentShaderReportsLabelAndLog) {
  auto ctx = Context::create();
  const char* broken = R"(#version 330 core
out vec4 color;
void main() { color = vec4(undeclared_variable, 1.0); }
)";
  try {
    glc::Program::link(ctx->gl(), kFullScreenVs, broken, "my-broken-shader");
    FAIL() << "expected GlError";
  } catch (const GlError& e) {
    const std::string msg = e.what();
    std::cout << "[ log      ] " << msg << "\n";
    EXPECT_NE(msg.find("my-broken-shader"), std::string::npos) << msg;
    EXPECT_NE(msg.find("fragment"), std::string::npos) << msg;
    EXPECT_NE(msg.find("error"), std::string::npos) << msg;
    EXPECT_NE(msg.find("undeclared_variable"), std::string::npos) << msg;
  }
}

TEST(Program, LinkErrorReportsLabel) {
  auto ctx = Context::create();
  // Compiles fine (a stage may consist of helpers only), but a program
  // without a fragment main() cannot link.
  const char* fs = R"(#version 330 core
float helper(float x) { return 2.0 * x; }
)";
  try {
    glc::Program::link(ctx->gl(), kFullScreenVs, fs, "link-fail");
    FAIL() << "expected GlError";
  } catch (const GlError& e) {
    EXPECT_NE(std::string(e.what()).find("link-fail"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("link"), std::string::npos) << e.what();
  }
}

// Fragment centers sit at (x + .5, y + .5) and row 0 of glReadPixels is y = 0;
// the DWT engine's texel addressing relies on both.
TEST(Render, R32FFragCoordExact) {
  auto ctx = Context::create();
  constexpr int kW = 7, kH = 5;
  const std::vector<float> px = render_r32f(*ctx, R"(#version 330 core
layout(location = 0) out float v;
void main() { v = gl_FragCoord.x + 1000.0 * gl_FragCoord.y; }
)",
                                            kW, kH);
  for (int y = 0; y < kH; ++y) {
    for (int x = 0; x < kW; ++x) {
      const float expected = (static_cast<float>(x) + 0.5f) + 1000.0f * (static_cast<float>(y) + 0.5f);
      EXPECT_EQ(px[static_cast<std::size_t>(y * kW + x)], expected) << "x=" << x << " y=" << y;
    }
  }
}

// Upload -> texelFetch at integer coordinates -> read back: exact floats,
// same orientation (rows of create_2d data are rows of glReadPixels output).
TEST(Render, R32FTexelFetchRoundTrip) {
  auto ctx = Context::create();
  constexpr int kW = 7, kH = 5;
  std::vector<float> data(kW * kH);
  for (std::size_t i = 0; i < data.size(); ++i) data[i] = 0.1f * static_cast<float>(i) - 1.7f;
  const glc::Texture input = glc::Texture::create_2d(ctx->gl(), kW, kH, GL_R32F, GL_RED, GL_FLOAT, data.data());
  EXPECT_EQ(input.width(), kW);
  EXPECT_EQ(input.height(), kH);
  const std::vector<float> px = render_r32f(*ctx, kFetchTimesTwoFs, kW, kH, &input);
  for (std::size_t i = 0; i < data.size(); ++i) EXPECT_EQ(px[i], 2.0f * data[i]) << "i=" << i;
}

// Odd-width 8-bit rows are tightly packed: create_2d must not assume the
// default 4-byte unpack alignment.
TEST(Render, R8OddWidthUpload) {
  auto ctx = Context::create();
  constexpr int kW = 3, kH = 3;
  const unsigned char data[kW * kH] = {10, 20, 30, 40, 50, 60, 70, 80, 90};
  const glc::Texture input = glc::Texture::create_2d(ctx->gl(), kW, kH, GL_R8, GL_RED, GL_UNSIGNED_BYTE, data);
  const std::vector<float> px = render_r32f(*ctx, R"(#version 330 core
uniform sampler2D src;
layout(location = 0) out float v;
void main() { v = round(255.0 * texelFetch(src, ivec2(gl_FragCoord.xy), 0).r); }
)",
                                            kW, kH, &input);
  for (int i = 0; i < kW * kH; ++i) EXPECT_EQ(px[static_cast<std::size_t>(i)], data[i]) << i;
}

TEST(Resources, IncompleteFramebufferNamesStatus) {
  auto ctx = Context::create();
  const glc::Texture no_storage = glc::Texture::create(ctx->gl());
  // Binding creates the texture object, still without any storage.
  ctx->gl().glBindTexture(GL_TEXTURE_2D, no_storage.id());
  glc::Framebuffer fbo = glc::Framebuffer::create(ctx->gl());
  try {
    fbo.attach_color(no_storage);
    FAIL() << "expected GlError";
  } catch (const GlError& e) {
    EXPECT_NE(std::string(e.what()).find("GL_FRAMEBUFFER_INCOMPLETE"), std::string::npos) << e.what();
  }
  ctx->gl().glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

TEST(Resources, MoveTransfersOwnership) {
  auto ctx = Context::create();
  glc::Buffer a = glc::Buffer::create(ctx->gl());
  const GLuint id = a.id();
  ASSERT_NE(id, 0u);
  glc::Buffer b = std::move(a);
  EXPECT_EQ(a.id(), 0u);  // NOLINT(bugprone-use-after-move): checking moved-from state
  EXPECT_FALSE(a);
  EXPECT_EQ(b.id(), id);
  glc::Buffer c;
  c = std::move(b);
  EXPECT_EQ(c.id(), id);
  c.reset();
  EXPECT_EQ(c.id(), 0u);
  glc::Query q = glc::Query::create(ctx->gl());
  EXPECT_NE(q.id(), 0u);
  glc::check(ctx->gl(), "resource lifetimes");
}

TEST(Resources, MultipleColorAttachments) {
  auto ctx = Context::create();
  const glc::GlApi& gl = ctx->gl();
  const glc::Texture lo = glc::Texture::create_2d(gl, 4, 2, GL_R32F, GL_RED, GL_FLOAT, nullptr);
  const glc::Texture hi = glc::Texture::create_2d(gl, 4, 2, GL_R32F, GL_RED, GL_FLOAT, nullptr);
  glc::Framebuffer fbo = glc::Framebuffer::create(gl);
  fbo.attach_color(lo, 0);
  fbo.attach_color(hi, 1);
  const glc::Program program = glc::Program::link(gl, kFullScreenVs, R"(#version 330 core
layout(location = 0) out float a;
layout(location = 1) out float b;
void main() { a = 1.0; b = 2.0; }
)",
                                                  "mrt");
  const glc::VertexArray vao = glc::VertexArray::create(gl);
  gl.glViewport(0, 0, 4, 2);
  program.use();
  vao.bind();
  gl.glDrawArrays(GL_TRIANGLES, 0, 3);
  float px[8] = {};
  gl.glReadBuffer(GL_COLOR_ATTACHMENT1);
  gl.glReadPixels(0, 0, 4, 2, GL_RED, GL_FLOAT, px);
  glc::check(gl, "mrt draw/read");
  for (float v : px) EXPECT_EQ(v, 2.0f);
  gl.glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

}  // namespace

// The key of --dwt auto's cost cache, read from made-up /dev, /proc and /sys trees.
namespace {

struct FakeRoot {
  test_support::ScratchDir dir{"gpuj2k_fake_root"};
  const std::filesystem::path& root = dir.path();
  void write(const std::string& relative, const std::string& text) const {
    const std::filesystem::path file = root / relative;
    std::filesystem::create_directories(file.parent_path());
    std::ofstream(file) << text;
  }
};

}  // namespace

TEST(GpuFingerprint, NoDeviceNodeMeansNoHardwareGpu) {
  FakeRoot fake;
  fake.write("proc/sys/kernel/osrelease", "6.1.0-28-amd64\n");
  EXPECT_EQ(glc::hardware_gpu_fingerprint(fake.root), "");
}

TEST(GpuFingerprint, NvidiaDriverVersionAndModels) {
  FakeRoot fake;
  fake.write("dev/nvidia0", "");
  fake.write("proc/driver/nvidia/version",
             "NVRM version: NVIDIA UNIX x86_64 Kernel Module  580.159.04  Tue Oct 14 2025\nGCC version: gcc 12\n");
  fake.write("proc/driver/nvidia/gpus/0000:00:05.0/information", "Model: \t\t NVIDIA H200\nIRQ: 42\n");
  EXPECT_EQ(glc::hardware_gpu_fingerprint(fake.root), "nvidia 580.159.04: NVIDIA H200");
  // A driver update is another key, so the costs are measured again.
  fake.write("proc/driver/nvidia/version", "NVRM version: NVIDIA UNIX x86_64 Kernel Module  590.10  Mon Jan 5 2026\n");
  EXPECT_EQ(glc::hardware_gpu_fingerprint(fake.root), "nvidia 590.10: NVIDIA H200");
}

TEST(GpuFingerprint, DrmRenderNodesWithTheirDeviceAndDriver) {
  FakeRoot fake;
  fake.write("dev/dri/card0", "");
  fake.write("dev/dri/renderD128", "");
  fake.write("sys/class/drm/renderD128/device/vendor", "0x1002\n");
  fake.write("sys/class/drm/renderD128/device/device", "0x744c\n");
  std::filesystem::create_directories(fake.root / "sys/bus/pci/drivers/amdgpu");
  std::filesystem::create_symlink(fake.root / "sys/bus/pci/drivers/amdgpu",
                                  fake.root / "sys/class/drm/renderD128/device/driver");
  fake.write("proc/sys/kernel/osrelease", "6.1.0-28-amd64\n");
  EXPECT_EQ(glc::hardware_gpu_fingerprint(fake.root), "drm renderD128 0x1002:0x744c amdgpu; kernel 6.1.0-28-amd64");
}
