# The performer's body (thesis 3.5-3.6): a skin mesh grown around any skeleton (implicit capsules,
# marching cubes, Taubin smoothing), binding it to the skeleton, and skinned meshes read from and
# written to glTF 2.0. Included from performer/CMakeLists.txt after gpuj2k_performer is defined;
# paths are spelled from this file so it also works when included from elsewhere.
#
# glTF goes through Debian's libtinygltf, which ships TinyGLTF compiled as a shared library (see
# /usr/share/doc/libtinygltf-dev/README.Debian): linking it gives the one implementation of the
# header, so no source here defines TINYGLTF_IMPLEMENTATION (doing so would also need nlohmann-json
# and stb headers). face.cmake links the same target; linking it twice is harmless.
find_package(TinyGLTF CONFIG REQUIRED)
target_sources(gpuj2k_performer PRIVATE
  ${CMAKE_CURRENT_LIST_DIR}/src/body_shape.cpp
  ${CMAKE_CURRENT_LIST_DIR}/src/scalar_grid.cpp
  ${CMAKE_CURRENT_LIST_DIR}/src/marching_cubes_cases.cpp
  ${CMAKE_CURRENT_LIST_DIR}/src/marching_cubes.cpp
  ${CMAKE_CURRENT_LIST_DIR}/src/mesh_smooth.cpp
  ${CMAKE_CURRENT_LIST_DIR}/src/body_mesh.cpp
  ${CMAKE_CURRENT_LIST_DIR}/src/skinned_mesh.cpp
  ${CMAKE_CURRENT_LIST_DIR}/src/body_weights.cpp
  ${CMAKE_CURRENT_LIST_DIR}/src/skeleton_skin.cpp
  ${CMAKE_CURRENT_LIST_DIR}/src/gltf_accessor.cpp
  ${CMAKE_CURRENT_LIST_DIR}/src/gltf_load.cpp
  ${CMAKE_CURRENT_LIST_DIR}/src/gltf_buffer_view.cpp
  ${CMAKE_CURRENT_LIST_DIR}/src/gltf_skin_read.cpp
  ${CMAKE_CURRENT_LIST_DIR}/src/gltf_skin_write.cpp)
# Private: no TinyGLTF type appears in the performer's headers.
target_link_libraries(gpuj2k_performer PRIVATE TinyGLTF::TinyGLTF)
