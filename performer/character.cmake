# The whole performer (thesis 3.6): the generated body and a face model merged into one mesh bound to
# the skeleton, and the per-frame integrated deformation of equation 3.20 (face first, then SSD).
# glTF avatars become characters too (avatar.cpp: skin and face as a Character, joints following a
# BVH clip by name; gltf_avatar_read.cpp: both read from one file). Included from
# performer/CMakeLists.txt after body.cmake and face.cmake, whose sources it builds on; paths are
# spelled from this file so it also works when included from elsewhere.
target_sources(gpuj2k_performer PRIVATE
  ${CMAKE_CURRENT_LIST_DIR}/src/character.cpp
  ${CMAKE_CURRENT_LIST_DIR}/src/character_deform.cpp
  ${CMAKE_CURRENT_LIST_DIR}/src/avatar.cpp
  ${CMAKE_CURRENT_LIST_DIR}/src/gltf_avatar_read.cpp)
