// Context creation: pick backends in order, load GL, verify 3.3 core.
#include "glcontext/context.h"

#include "backend.h"
#include "glcontext/error.h"
#include "glcontext/gpu_fingerprint.h"

#include <cctype>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace glc {
namespace {

std::unique_ptr<detail::Backend> create_backend(Platform platform, bool auto_mode) {
  switch (platform) {
    // An explicit egl-device request may fall back to Mesa's software device;
    // Auto must not, or it would never reach the later, intended fallbacks.
    case Platform::EglDevice:
      return detail::create_egl_device_backend(!auto_mode);
    case Platform::EglSurfaceless:
      return detail::create_egl_surfaceless_backend();
    case Platform::EglDefault:
      return detail::create_egl_default_backend();
    case Platform::OsMesa:
      return detail::create_osmesa_backend();
    case Platform::Auto:
      break;
  }
  throw GlError("internal: no backend for platform");
}

// Whether the system has a device node through which a driver could reach a GPU: a DRM node
// (/dev/dri/card*, /dev/dri/renderD*: Mesa's hardware drivers, NVIDIA's with DRM), NVIDIA's own
// (/dev/nvidia0) or WSL's /dev/dxg, which is what the fingerprint names. Without one no driver can,
// and asking EGL would only load Mesa's libraries to find its software device: a millisecond, 1 % of
// a small encode.
bool gpu_device_node_present() { return !hardware_gpu_fingerprint().empty(); }

std::string gl_string(const GlApi& gl, GLenum name) {
  const GLubyte* s = gl.glGetString(name);
  return s ? reinterpret_cast<const char*>(s) : "";
}

}  // namespace

std::unique_ptr<Context> Context::create(Platform platform) {
  const bool auto_mode = platform == Platform::Auto;
  std::vector<Platform> candidates;
  if (auto_mode) {
    candidates = {Platform::EglDevice, Platform::EglSurfaceless, Platform::EglDefault, Platform::OsMesa};
  } else {
    candidates = {platform};
  }

  std::string failures;
  for (Platform candidate : candidates) {
    try {
      // The constructor is private, hence no make_unique.
      return std::unique_ptr<Context>(new Context(candidate, create_backend(candidate, auto_mode)));
    } catch (const GlError& e) {
      if (!failures.empty()) failures += "; ";
      failures += std::string(platform_name(candidate)) + ": " + e.what();
    }
  }
  throw GlError("no OpenGL 3.3 core context: " + failures);
}

std::unique_ptr<Context> Context::create_hardware() {
  if (!gpu_device_node_present())
    throw GlError("no hardware GPU: no GPU device node (/dev/dri/card*, /dev/dri/renderD*, /dev/nvidia0, /dev/dxg)");
  std::unique_ptr<Context> context;
  try {
    context.reset(new Context(Platform::EglDevice, detail::create_egl_device_backend(false)));
  } catch (const GlError& e) {
    throw GlError(std::string("no hardware GPU: egl-device: ") + e.what());
  }
  // A device not flagged as software can still be one (a vendor ICD without the Mesa flag).
  if (is_software_renderer(context->renderer()))
    throw GlError("no hardware GPU: the only renderer is " + context->renderer() + ", a software rasteriser");
  return context;
}

bool is_software_renderer(std::string_view renderer) {
  std::string low(renderer);
  for (char& c : low) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  for (std::string_view name :
       {"llvmpipe", "softpipe", "swrast", "lavapipe", "swiftshader", "software rasterizer", "basic render driver"})
    if (low.find(name) != std::string::npos) return true;
  return false;
}

Context::Context(Platform platform, std::unique_ptr<detail::Backend> backend)
    : platform_(platform), backend_(std::move(backend)) {
  const detail::Backend& b = *backend_;
  load(gl_, [&b](const char* name) { return b.get_proc(name); });

  // The EGL/OSMesa attributes are requests; drivers may hand back something
  // else (e.g. a compatibility or older context), so verify what we got.
  GLint major = 0, minor = 0, profile = 0;
  gl_.glGetIntegerv(GL_MAJOR_VERSION, &major);
  gl_.glGetIntegerv(GL_MINOR_VERSION, &minor);
  gl_.glGetIntegerv(GL_CONTEXT_PROFILE_MASK, &profile);
  version_ = gl_string(gl_, GL_VERSION);
  if (major < 3 || (major == 3 && minor < 3) || !(profile & GL_CONTEXT_CORE_PROFILE_BIT)) {
    throw GlError("got OpenGL '" + version_ + "', need 3.3 core");
  }
  renderer_ = gl_string(gl_, GL_RENDERER);
  vendor_ = gl_string(gl_, GL_VENDOR);
  gl_.glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_texture_size_);
  check(gl_, "context setup queries");
}

// Out of line because detail::Backend is incomplete in the header.
Context::~Context() = default;

std::string Context::description() const {
  return renderer_ + " | " + version_ + " | " + std::string(platform_name(platform_));
}

void Context::make_current() { backend_->make_current(); }

void Context::release_current() noexcept { backend_->release_current(); }

}  // namespace glc
