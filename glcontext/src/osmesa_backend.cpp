// OSMesa (software) backend. libOSMesa is dlopen'ed so the binary starts, and
// the EGL paths work, on machines without it; <GL/osmesa.h> is used only for
// constants and function types, never linked.
#include "backend.h"
#include "glcontext/error.h"
#include "sanitizer_pin.h"

#include <GL/osmesa.h>
#include <dlfcn.h>

#include <string>
#include <vector>

namespace glc::detail {
namespace {

class OsMesaBackend final : public Backend {
 public:
  OsMesaBackend() {
    try {
      open_library();
      create_context();
    } catch (...) {
      release();  // the destructor does not run for a throwing constructor
      throw;
    }
  }
  ~OsMesaBackend() override { release(); }

  void* get_proc(const char* name) const override { return reinterpret_cast<void*>(get_proc_address_(name)); }

 protected:
  void bind() override {
    if (!osmesa_make_current_(context_, buffer_.data(), GL_UNSIGNED_BYTE, kSize, kSize)) {
      throw GlError("OSMesaMakeCurrent failed");
    }
  }

  // null context and buffer is OSMesa's "release" form.
  void unbind() noexcept override { osmesa_make_current_(nullptr, nullptr, 0, 0, 0); }

 private:
  // OSMesaMakeCurrent insists on a color buffer even though all rendering
  // goes to FBOs; keep it tiny.
  static constexpr int kSize = 4;

  template <class Fn>
  Fn symbol(const char* name) {
    void* p = dlsym(lib_, name);
    if (p == nullptr) throw GlError(std::string(name) + " not found in libOSMesa");
    return reinterpret_cast<Fn>(p);
  }

  void open_library() {
    // The versioned name is what runtime packages ship; the bare name only
    // comes with -dev packages but covers other distributions' sonames.
    for (const char* name : {"libOSMesa.so.8", "libOSMesa.so"}) {
      lib_ = dlopen(name, RTLD_NOW | RTLD_LOCAL);
      if (lib_ != nullptr) break;
    }
    if (lib_ == nullptr) throw GlError("libOSMesa.so.8 not found");
    pin_driver_libraries();
    create_ = symbol<decltype(&OSMesaCreateContextAttribs)>("OSMesaCreateContextAttribs");
    osmesa_make_current_ = symbol<decltype(&OSMesaMakeCurrent)>("OSMesaMakeCurrent");
    destroy_ = symbol<decltype(&OSMesaDestroyContext)>("OSMesaDestroyContext");
    get_proc_address_ = symbol<decltype(&OSMesaGetProcAddress)>("OSMesaGetProcAddress");
  }

  void create_context() {
    const int attribs[] = {
        OSMESA_FORMAT,
        OSMESA_RGBA,
        OSMESA_DEPTH_BITS,
        0,
        OSMESA_STENCIL_BITS,
        0,
        OSMESA_ACCUM_BITS,
        0,
        OSMESA_PROFILE,
        OSMESA_CORE_PROFILE,
        OSMESA_CONTEXT_MAJOR_VERSION,
        3,
        OSMESA_CONTEXT_MINOR_VERSION,
        3,
        0,
    };
    context_ = create_(attribs, nullptr);
    if (context_ == nullptr) throw GlError("OSMesaCreateContextAttribs(3.3 core) failed");
    buffer_.assign(static_cast<std::size_t>(kSize) * kSize * 4, 0);
    make_current();
  }

  void release() noexcept {
    if (context_ != nullptr) {
      release_current();  // only if current on this thread
      destroy_(context_);
      context_ = nullptr;
    }
    if (lib_ != nullptr) {
      dlclose(lib_);
      lib_ = nullptr;
    }
  }

  void* lib_ = nullptr;
  decltype(&OSMesaCreateContextAttribs) create_ = nullptr;
  decltype(&OSMesaMakeCurrent) osmesa_make_current_ = nullptr;
  decltype(&OSMesaDestroyContext) destroy_ = nullptr;
  decltype(&OSMesaGetProcAddress) get_proc_address_ = nullptr;
  OSMesaContext context_ = nullptr;
  std::vector<unsigned char> buffer_;
};

}  // namespace

std::unique_ptr<Backend> create_osmesa_backend() { return std::make_unique<OsMesaBackend>(); }

}  // namespace glc::detail
