# libFuzzer targets for the performer's file readers: BVH motion capture and Rhubarb Lip Sync
# (TSV and JSON). See gpuj2k_add_fuzzer in the top-level CMakeLists.txt (GPUJ2K_FUZZ).
gpuj2k_add_fuzzer(bvh_fuzz src/bvh.cpp src/bvh_lexer.cpp src/skeleton.cpp)
# The Rhubarb reader's file also maps cues to visemes, which pulls in the viseme tables.
gpuj2k_add_fuzzer(rhubarb_fuzz
  src/viseme_rhubarb.cpp src/viseme_rhubarb_json.cpp src/viseme_json.cpp src/viseme_text.cpp
  src/viseme_error.cpp src/phoneme_role.cpp src/viseme_library.cpp src/viseme_set.cpp src/viseme_table.cpp)
foreach(fuzzer bvh_fuzz rhubarb_fuzz)
  if(TARGET ${fuzzer})
    target_link_libraries(${fuzzer} PRIVATE glm::glm)
    target_compile_definitions(${fuzzer} PRIVATE GPUJ2K_PERFORMER_DATA_DIR="${CMAKE_CURRENT_LIST_DIR}/data")
  endif()
endforeach()
