#include "summary.h"

#include <cstdio>

#include "dwt/boundary.h"
#include "dwt/kernel.h"

namespace dwtool {

std::string summary_line(Direction direction, const dwt::DwtParams& params, int width, int height,
                         const std::string& backend_name, double milliseconds) {
  char time[32];
  std::snprintf(time, sizeof time, "%.2f", milliseconds);
  return std::string(direction == Direction::Forward ? "forward " : "inverse ") +
         std::string(dwt::get_kernel(params.kernel).name) + " " + std::string(dwt::boundary_name(params.boundary)) +
         " " + std::to_string(params.levels) + (params.levels == 1 ? " level " : " levels ") + std::to_string(width) +
         "x" + std::to_string(height) + " origin (" + std::to_string(params.origin.x) + "," +
         std::to_string(params.origin.y) + ") on " + backend_name + ": " + time + " ms";
}

}  // namespace dwtool
