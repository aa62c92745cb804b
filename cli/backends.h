// Choosing the wavelet backend a request names, and refusing kernels it cannot run.
#pragma once

#include <memory>
#include <string>

#include "dwt/backend.h"
#include "request.h"

namespace dwtool {

// Cheap: the GPU backend's GL context is only created by prepare(). Throws with a one-line message
// when the backend does not exist in this build or does not support the request's kernel.
std::unique_ptr<dwt::DwtBackend> make_backend(const Request& request);

// Does the expensive one-time set-up (the GPU's GL context) before the transform is timed, and
// returns the GL renderer line for the GPU backend, an empty string for the CPU.
std::string prepare(dwt::DwtBackend& backend);

// Where the time of the last transform went, for backends that measure it (the GPU: upload, render
// passes, read-back), as " (...)" to append to the summary; empty for the CPU.
std::string stage_times(const dwt::DwtBackend& backend);

}  // namespace dwtool
