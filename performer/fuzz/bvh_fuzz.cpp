// libFuzzer entry point for the BVH reader. Rejected input must surface as BvhError; any other
// exception, crash or sanitizer report is a bug, and so is an accepted file that breaks the
// reader's promises (parents before children, channel offsets that tile a motion row, a motion
// block of exactly frames x channels values, a positive frame time).
//
//   cmake -DCMAKE_CXX_COMPILER=clang++ -DGPUJ2K_FUZZ=ON ... && build/bin/bvh_fuzz

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "performer/bvh.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    const performer::Bvh bvh =
        performer::parse_bvh(std::string_view(reinterpret_cast<const char*>(data), size), "fuzz-input");
    const auto& joints = bvh.skeleton.joints;
    int next_channel = 0;
    for (std::size_t i = 0; i < joints.size(); ++i) {
      if (joints[i].parent >= static_cast<int>(i) || joints[i].parent < -1) std::abort();
      if (joints[i].channel_offset != next_channel) std::abort();
      next_channel += static_cast<int>(joints[i].channels.size());
    }
    if (next_channel != performer::channel_count(bvh.skeleton)) std::abort();
    if (bvh.motion.frames < 0) std::abort();
    if (bvh.motion.values.size() !=
        static_cast<std::size_t>(bvh.motion.frames) * static_cast<std::size_t>(next_channel))
      std::abort();
    if (!(bvh.motion.frame_time > 0) || !std::isfinite(bvh.motion.frame_time)) std::abort();
    for (float v : bvh.motion.values)
      if (!std::isfinite(v)) std::abort();
  } catch (const performer::BvhError&) {
    // Expected for malformed input.
  }
  return 0;
}
