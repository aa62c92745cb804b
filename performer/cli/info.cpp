#include "info.h"

#include <algorithm>

namespace performer::cli {

void print_info(const Bvh& bvh, const std::string& path, std::FILE* out) {
  const Skeleton& skeleton = bvh.skeleton;
  const Motion& motion = bvh.motion;
  const int end_sites = static_cast<int>(skeleton.joints.size()) - animated_joint_count(skeleton);
  std::fprintf(out, "file: %s\n", path.c_str());
  std::fprintf(out, "joints: %d (plus %d end sites)\n", animated_joint_count(skeleton), end_sites);

  // Columns sized to the longest name so the table reads at a glance.
  std::size_t width = 4;
  for (const Joint& j : skeleton.joints) width = std::max(width, j.name.size());
  const int w = static_cast<int>(width);
  std::fprintf(out, "  %3s  %-*s  %-*s  %s\n", "#", w, "name", w, "parent", "channels");
  for (std::size_t i = 0; i < skeleton.joints.size(); ++i) {
    const Joint& j = skeleton.joints[i];
    const std::string parent = j.parent < 0 ? "-" : skeleton.joints[static_cast<std::size_t>(j.parent)].name;
    std::string channels;
    for (const Channel c : j.channels) {
      if (!channels.empty()) channels += ' ';
      channels += channel_name(c);
    }
    if (j.end_site)
      channels = "(end site)";
    else if (channels.empty())
      channels = "(none)";
    std::fprintf(out, "  %3zu  %-*s  %-*s  %s\n", i, w, j.name.c_str(), w, parent.c_str(), channels.c_str());
  }
  std::fprintf(out, "channels: %d\n", channel_count(skeleton));
  std::fprintf(out, "frames: %d\n", motion.frames);
  std::fprintf(out, "frame time: %.7g s (%.3f fps)\n", motion.frame_time, 1.0 / motion.frame_time);
  // Playback length counts every frame for one frame time; sampling stops at the last frame's time.
  std::fprintf(out, "duration: %.3f s (last frame at %.3f s)\n", motion.frames * motion.frame_time,
               last_frame_time(motion));
}

}  // namespace performer::cli
