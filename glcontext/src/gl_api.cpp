#include "glcontext/gl_api.h"

#include "glcontext/error.h"

#include <string>

namespace glc {

void load(GlApi& api, const ProcLoader& loader) {
  GlApi loaded;
  std::string missing;
  // Function pointers are cast from void* (POSIX guarantees this round-trips);
  // every missing name is collected so one error reports all of them.
#define GLC_LOAD_MEMBER(type, name)                  \
  if (void* p = loader(#name)) {                     \
    loaded.name = reinterpret_cast<type>(p);         \
  } else {                                           \
    missing += missing.empty() ? #name : ", " #name; \
  }
  GLC_GL_FUNCTIONS(GLC_LOAD_MEMBER)
#undef GLC_LOAD_MEMBER
  if (!missing.empty()) throw GlError("missing GL functions: " + missing);
  api = loaded;
}

}  // namespace glc
