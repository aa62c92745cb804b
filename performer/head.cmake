# The procedural head and the mesh writers, as a library of their own: plain geometry (the face
# model and its deformation vectors, the viseme set that names them, normals, OBJ/PLY writers),
# MIT and free of the performer's GPL and glTF dependencies, so that other components (dwtool's
# built-in control net) take them without linking speech or video. gpuj2k_performer builds on it.
# Included from performer/CMakeLists.txt before gpuj2k_performer is defined; the sources are the
# performer's (src/), which its other parts share internal headers with.
add_library(gpuj2k_performer_head STATIC
  ${CMAKE_CURRENT_LIST_DIR}/src/phoneme_role.cpp
  ${CMAKE_CURRENT_LIST_DIR}/src/viseme_error.cpp
  ${CMAKE_CURRENT_LIST_DIR}/src/viseme_text.cpp
  ${CMAKE_CURRENT_LIST_DIR}/src/viseme_set.cpp
  ${CMAKE_CURRENT_LIST_DIR}/src/face_model.cpp
  ${CMAKE_CURRENT_LIST_DIR}/src/mesh_normals.cpp
  ${CMAKE_CURRENT_LIST_DIR}/src/atomic_file.cpp
  ${CMAKE_CURRENT_LIST_DIR}/src/mesh_io.cpp
  ${CMAKE_CURRENT_LIST_DIR}/src/head_grid.cpp
  ${CMAKE_CURRENT_LIST_DIR}/src/head_shape.cpp
  ${CMAKE_CURRENT_LIST_DIR}/src/head_pose.cpp
  ${CMAKE_CURRENT_LIST_DIR}/src/head_poses.cpp
  ${CMAKE_CURRENT_LIST_DIR}/src/procedural_head.cpp)
target_include_directories(gpuj2k_performer_head PUBLIC ${CMAKE_CURRENT_LIST_DIR}/include
                           PRIVATE ${CMAKE_CURRENT_LIST_DIR}/src)
target_link_libraries(gpuj2k_performer_head PUBLIC glm::glm gpuj2k_base)
