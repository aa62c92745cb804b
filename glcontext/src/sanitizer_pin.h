// Internal: keep GL driver libraries mapped in AddressSanitizer builds.
//
// eglTerminate makes Mesa dlclose its DRI driver, and our OSMesa backend
// dlcloses libOSMesa. Both libraries leak a little internal memory, and once
// unloaded LeakSanitizer can only print "<unknown module>" for it, which no
// suppression rule can match (GCC 12's libasan). Under ASan we therefore add
// a permanent reference to those libraries so they stay mapped: their leaks
// are then either reachable through the library's globals or attributed to a
// named library. Normal builds unload as usual.
#pragma once

namespace glc::detail {

// No-op unless built with -fsanitize=address.
void pin_driver_libraries() noexcept;

}  // namespace glc::detail
