#pragma once
#include <cstddef>
#include <string>

namespace performer::render {

// The vertex shader of equation 3.20 (see deform_shader.cpp): `joints` bone matrices in a uniform
// block, or fetched from a buffer texture when `bones_in_texture`; `face_slots` DV streams.
std::string deform_vertex_shader(std::size_t joints, bool bones_in_texture, int face_slots);

// Attribute locations the shader declares.
inline constexpr unsigned kRestPositionAttribute = 0;
inline constexpr unsigned kRestNormalAttribute = 1;
inline constexpr unsigned kJointsAttribute = 2;
inline constexpr unsigned kWeightsAttribute = 3;
inline constexpr unsigned kFirstPositionDvAttribute = 4;  // then one per face slot
// the normal DVs follow the position DVs: kFirstPositionDvAttribute + face_slots + slot

}  // namespace performer::render
