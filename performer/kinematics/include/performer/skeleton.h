// The performer's skeleton and motion as plain data: what a BVH file holds, laid out so that the
// jobs (local_transforms, world_transforms, sample, ...) can walk it front to back without lookups.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <glm/vec3.hpp>

namespace performer {

// One animated degree of freedom. Rotations are in degrees, as BVH stores them; the jobs convert.
enum class Channel : std::uint8_t { Xposition, Yposition, Zposition, Xrotation, Yrotation, Zrotation };

// The BVH spelling ("Xposition", ...), for messages and the CLI.
std::string_view channel_name(Channel channel);

inline bool is_rotation(Channel channel) { return channel >= Channel::Xrotation; }

// 0, 1, 2 for X, Y, Z: the component of a position channel, or the axis of a rotation channel.
inline int channel_axis(Channel channel) { return static_cast<int>(channel) % 3; }

struct Joint {
  std::string name;               // BVH name; an end site is named after its parent plus "_end"
  int parent = -1;                // index into Skeleton::joints, -1 for a root
  glm::vec3 offset{0.0f};         // rest position relative to the parent joint
  std::vector<Channel> channels;  // in file order, which is also the order rotations multiply in
  int channel_offset = 0;         // index of this joint's first value within a motion row
  bool end_site = false;          // BVH "End Site": a leaf that only marks where the last bone ends
};

struct Skeleton {
  // Depth-first file order, so parents come before children: a single forward pass over the array
  // can accumulate world transforms. Several roots are allowed (parent -1 each).
  std::vector<Joint> joints;
};

struct Motion {
  int frames = 0;           // number of rows
  double frame_time = 0.0;  // seconds between rows
  // frames * channel_count(skeleton) values, row after row, each row in Joint::channel_offset order.
  std::vector<float> values;
};

// Number of values in one motion row (the sum of all joints' channel counts).
int channel_count(const Skeleton& skeleton);

// Number of joints that are not end sites (what BVH tools usually call the joint count).
int animated_joint_count(const Skeleton& skeleton);

// Index of the first joint called `name`, or -1.
int find_joint(const Skeleton& skeleton, std::string_view name);

// The values of row `frame` (0-based). Throws std::out_of_range for a frame outside the motion and
// std::invalid_argument when the motion does not hold frames * channel_count values.
std::span<const float> frame_values(const Skeleton& skeleton, const Motion& motion, int frame);

// Time of the last frame, (frames - 1) * frame_time: sample() clamps to [0, this].
double last_frame_time(const Motion& motion);

}  // namespace performer
