// Sampling a motion at any time, between its rows (thesis 3.5.3: playing motion capture on a
// character whose frame rate is not the capture's).
#pragma once

#include <span>

#include "performer/pose.h"
#include "performer/skeleton.h"

namespace performer {

// Poses at `seconds`: the two surrounding rows blended (translation linearly, rotation by shortest
// arc slerp). Times outside [0, last_frame_time(motion)] clamp to the first or last row, and a time
// within 1e-6 of a frame of a row returns that row's pose exactly.
// A motion with no frames yields the rest pose (offsets, identity rotations).
// Throws std::invalid_argument on size mismatches or a motion whose values do not fit the skeleton.
void sample(const Skeleton& skeleton, const Motion& motion, double seconds, std::span<JointPose> out);

}  // namespace performer
