#pragma once
// The library's one error type at its boundary: whatever the components throw leaves the public
// functions as gpuj2k::Error, its message one line (the cause's own, after `prefix`).
#include <new>
#include <stdexcept>
#include <string>

#include "gpuj2k/common.h"

namespace gpuj2k::detail {

template <class Work>
auto as_library_error(const std::string& prefix, Work&& work) -> decltype(work()) {
  try {
    return work();
  } catch (const Error&) {
    throw;
  } catch (const std::bad_alloc&) {
    throw Error(prefix + "out of memory");
  } catch (const std::exception& e) {
    throw Error(prefix + e.what());
  }
}

}  // namespace gpuj2k::detail
