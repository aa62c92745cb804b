// One dwtool run end to end: read, check, transform, write, report.
#pragma once

#include "request.h"

namespace dwtool {

// Throws std::exception with a one-line message (naming the file concerned, where there is one) on
// any failure. The output file is written only after the transform succeeded, and atomically.
void run(const Request& request);

}  // namespace dwtool
