# libFuzzer targets for the performer's file readers: BVH motion capture and Rhubarb Lip Sync
# (TSV and JSON). Like imageio's PFM/PNM fuzzers they compile the readers' sources themselves, so
# that those get the fuzzer's coverage instrumentation; libFuzzer ships with Clang only. Built
# with -DGPUJ2K_FUZZ=ON (the option is declared in imageio/CMakeLists.txt).
if(GPUJ2K_FUZZ)
  if(CMAKE_CXX_COMPILER_ID MATCHES "Clang")
    set(GPUJ2K_BVH_FUZZ_SOURCES src/bvh.cpp src/bvh_lexer.cpp src/skeleton.cpp)
    # The Rhubarb reader's file also maps cues to visemes, which pulls in the viseme tables.
    set(GPUJ2K_RHUBARB_FUZZ_SOURCES
      src/viseme_rhubarb.cpp src/viseme_rhubarb_json.cpp src/viseme_json.cpp src/viseme_text.cpp
      src/viseme_error.cpp src/phoneme_role.cpp src/viseme_library.cpp src/viseme_set.cpp src/viseme_table.cpp)
    foreach(reader bvh rhubarb)
      string(TOUPPER ${reader} READER)
      add_executable(${reader}_fuzz fuzz/${reader}_fuzz.cpp ${GPUJ2K_${READER}_FUZZ_SOURCES})
      target_include_directories(${reader}_fuzz PRIVATE
        ${CMAKE_CURRENT_LIST_DIR}/include ${CMAKE_CURRENT_LIST_DIR}/src)
      target_link_libraries(${reader}_fuzz PRIVATE glm::glm)
      target_compile_definitions(${reader}_fuzz PRIVATE GPUJ2K_PERFORMER_DATA_DIR="${CMAKE_CURRENT_LIST_DIR}/data")
      target_compile_options(${reader}_fuzz PRIVATE -fsanitize=fuzzer,address,undefined)
      target_link_options(${reader}_fuzz PRIVATE -fsanitize=fuzzer,address,undefined)
    endforeach()
  else()
    message(WARNING "GPUJ2K_FUZZ needs Clang (libFuzzer); the BVH and Rhubarb fuzzers are not built")
  endif()
endif()
