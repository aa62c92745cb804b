// The three ways we obtain an EGLDisplay: a device, Mesa's surfaceless
// platform, or the vendor default. Context creation itself is EglBackend.
#include "backend.h"
#include "egl_backend.h"
#include "egl_util.h"
#include "glcontext/error.h"

#include <string>
#include <vector>

namespace glc::detail {
namespace {

PFNEGLGETPLATFORMDISPLAYEXTPROC platform_display_fn() {
  if (!has_extension(client_extensions(), "EGL_EXT_platform_base")) {
    throw GlError("EGL_EXT_platform_base not supported");
  }
  auto fn = egl_proc<PFNEGLGETPLATFORMDISPLAYEXTPROC>("eglGetPlatformDisplayEXT");
  if (fn == nullptr) throw GlError("eglGetPlatformDisplayEXT not found");
  return fn;
}

struct Device {
  EGLDeviceEXT handle;
  bool software;
  std::string name;  // DRM node when known, for error messages
};

std::vector<Device> enumerate_devices() {
  const char* ext = client_extensions();
  if (!has_extension(ext, "EGL_EXT_device_enumeration") && !has_extension(ext, "EGL_EXT_device_base")) {
    throw GlError("EGL_EXT_device_enumeration not supported");
  }
  if (!has_extension(ext, "EGL_EXT_platform_device")) {
    throw GlError("EGL_EXT_platform_device not supported");
  }
  auto query_devices = egl_proc<PFNEGLQUERYDEVICESEXTPROC>("eglQueryDevicesEXT");
  auto query_string = egl_proc<PFNEGLQUERYDEVICESTRINGEXTPROC>("eglQueryDeviceStringEXT");
  if (query_devices == nullptr || query_string == nullptr) {
    throw GlError("eglQueryDevicesEXT/eglQueryDeviceStringEXT not found");
  }

  EGLint count = 0;
  if (!query_devices(0, nullptr, &count)) throw GlError(egl_failure("eglQueryDevicesEXT"));
  std::vector<EGLDeviceEXT> handles(static_cast<std::size_t>(count));
  if (count > 0 && !query_devices(count, handles.data(), &count)) {
    throw GlError(egl_failure("eglQueryDevicesEXT"));
  }
  handles.resize(static_cast<std::size_t>(count));

  std::vector<Device> devices;
  for (std::size_t i = 0; i < handles.size(); ++i) {
    const char* dev_ext = query_string(handles[i], EGL_EXTENSIONS);
    Device d{handles[i], has_extension(dev_ext, "EGL_MESA_device_software"), "device " + std::to_string(i)};
    if (has_extension(dev_ext, "EGL_EXT_device_drm")) {
      if (const char* node = query_string(handles[i], EGL_DRM_DEVICE_FILE_EXT)) {
        d.name += " (" + std::string(node) + ")";
      }
    }
    devices.push_back(std::move(d));
  }
  return devices;
}

}  // namespace

std::unique_ptr<Backend> create_egl_device_backend(bool allow_software) {
  const std::vector<Device> devices = enumerate_devices();
  if (devices.empty()) throw GlError("no devices");
  const auto get_display = platform_display_fn();

  // Hardware first; Mesa's software device only when explicitly allowed
  // (in Auto mode the surfaceless platform reaches llvmpipe anyway).
  std::vector<const Device*> order;
  int skipped = 0;
  for (const Device& d : devices) {
    if (!d.software) order.push_back(&d);
  }
  for (const Device& d : devices) {
    if (d.software && allow_software) order.push_back(&d);
    if (d.software && !allow_software) ++skipped;
  }
  if (order.empty()) {
    throw GlError("no non-software devices (" + std::to_string(skipped) + " software device(s) skipped)");
  }

  std::string failures;
  for (const Device* d : order) {
    try {
      EGLDisplay dpy = get_display(EGL_PLATFORM_DEVICE_EXT, d->handle, nullptr);
      if (dpy == EGL_NO_DISPLAY) throw GlError(egl_failure("eglGetPlatformDisplayEXT"));
      return std::make_unique<EglBackend>(dpy);
    } catch (const GlError& e) {
      if (!failures.empty()) failures += ", ";
      failures += d->name + ": " + e.what();
    }
  }
  throw GlError(failures);
}

std::unique_ptr<Backend> create_egl_surfaceless_backend() {
  if (!has_extension(client_extensions(), "EGL_MESA_platform_surfaceless")) {
    throw GlError("EGL_MESA_platform_surfaceless not supported");
  }
  const auto get_display = platform_display_fn();
  EGLDisplay dpy = get_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
  if (dpy == EGL_NO_DISPLAY) throw GlError(egl_failure("eglGetPlatformDisplayEXT"));
  return std::make_unique<EglBackend>(dpy);
}

std::unique_ptr<Backend> create_egl_default_backend() {
  EGLDisplay dpy = eglGetDisplay(EGL_DEFAULT_DISPLAY);
  if (dpy == EGL_NO_DISPLAY) throw GlError(egl_failure("eglGetDisplay(EGL_DEFAULT_DISPLAY)"));
  return std::make_unique<EglBackend>(dpy);
}

}  // namespace glc::detail
