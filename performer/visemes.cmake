# Lip sync for the virtual performer (thesis 3.4.2-3.4.5): phoneme -> viseme tables read from
# data/visemes, syllable splitting, timing from keyframe files and Rhubarb Lip Sync, and blending
# weights with coarticulation, expressions and blinks. Included from performer/CMakeLists.txt after
# gpuj2k_performer is defined; paths are spelled from this file so it also works when included
# from elsewhere.
target_sources(gpuj2k_performer PRIVATE
  ${CMAKE_CURRENT_LIST_DIR}/src/phoneme_keyframes.cpp
  ${CMAKE_CURRENT_LIST_DIR}/src/viseme_table.cpp
  ${CMAKE_CURRENT_LIST_DIR}/src/viseme_library.cpp
  ${CMAKE_CURRENT_LIST_DIR}/src/viseme_json.cpp
  ${CMAKE_CURRENT_LIST_DIR}/src/viseme_rhubarb.cpp
  ${CMAKE_CURRENT_LIST_DIR}/src/viseme_rhubarb_json.cpp
  ${CMAKE_CURRENT_LIST_DIR}/src/syllable_split.cpp
  ${CMAKE_CURRENT_LIST_DIR}/src/syllable_parse.cpp
  ${CMAKE_CURRENT_LIST_DIR}/src/syllable_visemes.cpp
  ${CMAKE_CURRENT_LIST_DIR}/src/weights_curves.cpp
  ${CMAKE_CURRENT_LIST_DIR}/src/weights_visemes.cpp
  ${CMAKE_CURRENT_LIST_DIR}/src/weights_expression.cpp
  ${CMAKE_CURRENT_LIST_DIR}/src/weights_track.cpp
  ${CMAKE_CURRENT_LIST_DIR}/src/weights_oculus.cpp
  ${CMAKE_CURRENT_LIST_DIR}/src/weights_output.cpp
  ${CMAKE_CURRENT_LIST_DIR}/src/weights_input.cpp
  ${CMAKE_CURRENT_LIST_DIR}/src/blink_generator.cpp)
# The source tree's data folder, so tests and uninstalled builds find the tables with no setup;
# $GPUJ2K_PERFORMER_DATA overrides it at run time (viseme_library.h). Nothing is installed.
target_compile_definitions(gpuj2k_performer PRIVATE
  GPUJ2K_PERFORMER_DATA_DIR="${CMAKE_CURRENT_LIST_DIR}/data")
