#pragma once

// The GLSL of the renderer (renderer.cpp says what each pass draws).
namespace performer::render::shaders {

extern const char* const kCharacterVertex;  // character, outline and hair shells
extern const char* const kCharacterFragment;
extern const char* const kOutlineFragment;
extern const char* const kHairFragment;
extern const char* const kSkyVertex;
extern const char* const kSkyFragment;
extern const char* const kFloorVertex;
extern const char* const kFloorFragment;
extern const char* const kSnowVertex;
extern const char* const kSnowFragment;

}  // namespace performer::render::shaders
