#pragma once
#include <stdexcept>
#include <string>

namespace codec::cs {

// Raised when a marker segment, tile-part or JP2 box cannot be written as asked: a field outside
// the range T.800 allows, a length that does not fit its field, or markers that contradict each
// other. The message is one line naming the field and the limit.
class CodestreamError : public std::runtime_error {
 public:
  explicit CodestreamError(const std::string& what) : std::runtime_error(what) {}
};

}  // namespace codec::cs
