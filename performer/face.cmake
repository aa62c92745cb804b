# Facial animation for the virtual performer (thesis 3.4.1, 3.4.4-3.4.5): face models made of a
# neutral mesh plus deformation vectors, a procedural head with the thesis' viseme and expression
# targets, the per-frame blend (equations 3.9 and 3.11), mesh writers, and glTF 2.0 avatars with
# morph targets. Included from performer/CMakeLists.txt after gpuj2k_performer is defined; paths are
# spelled from this file so it also works when included from elsewhere.
#
# glTF goes through TinyGLTF. Debian's libtinygltf-dev ships it as a shared library with a CMake
# package, so nothing here defines TINYGLTF_IMPLEMENTATION and neither nlohmann-json nor stb
# headers are needed at build time. The glTF accessor reader, GltfError and area_weighted_normals
# come from the body's sources (body.cmake: gltf_accessor.cpp, gltf_load.cpp, gltf_skin_read.cpp,
# mesh_normals.cpp), which are part of the same library.
find_package(TinyGLTF CONFIG)
if(NOT TinyGLTF_FOUND)
  message(FATAL_ERROR "TinyGLTF not found: install libtinygltf-dev (glTF avatars for the performer's face)")
endif()

target_sources(gpuj2k_performer PRIVATE
  ${CMAKE_CURRENT_LIST_DIR}/src/face_deform.cpp
  ${CMAKE_CURRENT_LIST_DIR}/src/morph_mapping.cpp
  ${CMAKE_CURRENT_LIST_DIR}/src/gltf_face_read.cpp
  ${CMAKE_CURRENT_LIST_DIR}/src/gltf_face_write.cpp)
# Private: TinyGLTF types never appear in the performer's headers.
target_link_libraries(gpuj2k_performer PRIVATE TinyGLTF::TinyGLTF)
