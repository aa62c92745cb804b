#pragma once
#include <string>

#include "codec/codestream/error.h"

namespace codec::cs {

// Throws CodestreamError("who: what"), `who` naming the marker segment being written.
[[noreturn]] inline void fail(const char* who, const std::string& what) {
  throw CodestreamError(std::string(who) + ": " + what);
}

}  // namespace codec::cs
