// Headless OpenGL 3.3+ core-profile context (EGL or OSMesa), no window system.
#pragma once

#include "glcontext/gl_api.h"

#include <memory>
#include <string>
#include <string_view>

namespace glc {

// Where the context comes from.
//   EglDevice      - EGL_EXT_platform_device: a GPU picked without X/Wayland
//                    (the NVIDIA headless path).
//   EglSurfaceless - EGL_MESA_platform_surfaceless (Mesa: GPU via DRM render
//                    nodes, else llvmpipe).
//   EglDefault     - eglGetDisplay(EGL_DEFAULT_DISPLAY), whatever the EGL
//                    vendor chooses.
//   OsMesa         - libOSMesa, loaded with dlopen at run time (software).
//   Auto           - the first of the above that works, in that order, with
//                    EglDevice restricted to non-software devices.
enum class Platform { Auto, EglDevice, EglSurfaceless, EglDefault, OsMesa };

// Accepts "auto", "egl-device", "egl-surfaceless", "egl-default", "osmesa";
// anything else throws GlError listing those names.
Platform parse_platform(std::string_view name);

// The name parse_platform accepts for `platform`.
std::string_view platform_name(Platform platform);

// Platform named by the environment variable GPUJ2K_GL; unset or empty means
// Auto. Throws GlError for an unknown name (a typo should not silently fall
// back to another renderer).
Platform platform_from_env();

// Whether a GL_RENDERER string names a software rasteriser (Mesa's llvmpipe, softpipe and swrast,
// lavapipe, SwiftShader, Microsoft's Basic Render Driver): a renderer that runs on the CPU, useful
// to prove a GPU path correct, never to make it fast.
bool is_software_renderer(std::string_view renderer);

namespace detail {
class Backend;
}

// One OpenGL context, current on the creating thread after create().
//
// Neither copyable nor movable: resources (glc::Texture, ...) keep a pointer
// to gl(), so the Context must stay at one address; hold it by unique_ptr.
// Destroy every resource before its Context, and destroy a Context on the
// thread where it is current (or after release_current() on every other
// thread). Never keep GL resources (textures, programs, a dwt_gpu::GpuBackend) in a static object:
// with NVIDIA's driver the GL calls their destructors make inside exit() crash (seen on an H200).
// Contexts of different platforms may coexist in one process:
// make_current() switches correctly between EGL and OSMesa ones.
class Context {
 public:
  // Creates a context for `platform` and makes it current on this thread
  // (releasing whichever Context was current here before). Throws GlError
  // naming every platform tried and why each failed.
  static std::unique_ptr<Context> create(Platform platform = Platform::Auto);

  // A context on a hardware GPU, never a software rasteriser: the EGL device platform's
  // non-software devices only (NVIDIA's headless path, and Mesa's DRM devices). Cheap to refuse on
  // a machine without one: with no GPU device node (/dev/dri, /dev/nvidia0, /dev/dxg) EGL is not
  // even loaded, and enumerating the devices creates no context. Throws GlError saying what was
  // found instead.
  static std::unique_ptr<Context> create_hardware();

  ~Context();
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;
  Context(Context&&) = delete;
  Context& operator=(Context&&) = delete;

  const GlApi& gl() const noexcept { return gl_; }

  // Strings are captured at creation, so these work from any thread and
  // without the context being current.
  std::string renderer() const { return renderer_; }  // GL_RENDERER
  std::string vendor() const { return vendor_; }      // GL_VENDOR
  std::string version() const { return version_; }    // GL_VERSION
  // The platform actually used; never Platform::Auto.
  Platform platform() const noexcept { return platform_; }
  // "<renderer> | <version> | <platform name>", one line for logs.
  std::string description() const;
  int max_texture_size() const noexcept { return max_texture_size_; }

  // Makes this context current on the calling thread (needed after another
  // Context was made current, or to use this one from another thread; an
  // EGL/OSMesa context can be current on only one thread at a time).
  void make_current();
  // Unbinds this context from the calling thread if it is current there, so
  // another thread may make_current() it. No-op otherwise.
  void release_current() noexcept;

 private:
  Context(Platform platform, std::unique_ptr<detail::Backend> backend);

  Platform platform_;
  std::unique_ptr<detail::Backend> backend_;
  GlApi gl_;
  std::string renderer_;
  std::string vendor_;
  std::string version_;
  int max_texture_size_ = 0;
};

}  // namespace glc
