// The one line dwtool prints after a successful run.
#pragma once

#include <string>

#include "dwt/params.h"
#include "request.h"

namespace dwtool {

// e.g. "forward 97 sym 5 levels 512x512 origin (0,0) on cpu lifting (AVX2, 2 threads): 3.21 ms"
std::string summary_line(Direction direction, const dwt::DwtParams& params, int width, int height,
                         const std::string& backend_name, double milliseconds);

}  // namespace dwtool
