# libFuzzer targets for the performer's file readers: BVH motion capture and Rhubarb Lip Sync
# (TSV and JSON). See gpuj2k_add_fuzzer in the top-level CMakeLists.txt (GPUJ2K_FUZZ). Each compiles
# its reader's sources from the part that owns them.
gpuj2k_add_fuzzer(bvh_fuzz kinematics/src/bvh.cpp kinematics/src/bvh_lexer.cpp kinematics/src/skeleton.cpp)
# The Rhubarb reader's file also maps cues to visemes, which pulls in the viseme tables.
gpuj2k_add_fuzzer(rhubarb_fuzz
  visemes/src/viseme_rhubarb.cpp visemes/src/viseme_rhubarb_json.cpp visemes/src/viseme_json.cpp
  visemes/src/viseme_text.cpp visemes/src/viseme_error.cpp visemes/src/phoneme_role.cpp
  visemes/src/viseme_library.cpp visemes/src/viseme_set.cpp visemes/src/viseme_table.cpp)
if(TARGET bvh_fuzz)
  target_include_directories(bvh_fuzz PRIVATE kinematics/include kinematics/src)
  target_link_libraries(bvh_fuzz PRIVATE glm::glm)
endif()
if(TARGET rhubarb_fuzz)
  target_include_directories(rhubarb_fuzz PRIVATE visemes/include visemes/src)
  target_compile_definitions(rhubarb_fuzz PRIVATE GPUJ2K_PERFORMER_DATA_DIR="${CMAKE_CURRENT_LIST_DIR}/data")
endif()
