# Text to speech for the performer: espeak-ng speaks the text and reports its phonemes, which are
# mapped to visemes through data/espeak/<voice>.tsv (the thesis drives its lip sync from its TTS'
# timings, 3.4.3), and the audio is written as WAV. Included from performer/CMakeLists.txt after
# gpuj2k_performer is defined; paths are spelled from this file.
#
# Licence: espeak-ng is GPL-3.0-or-later. It is linked into gpuj2k_performer only, PRIVATE, and
# must never be linked into the codec libraries or tools, which stay MIT. Any program linking
# gpuj2k_performer (the performer tool, its tests) is therefore a combined work under the GPL.
#
# Debian: libespeak-ng-dev to build (headers, library, espeak-ng.pc), espeak-ng-data at run time.
find_package(PkgConfig QUIET)
if(PkgConfig_FOUND)
  pkg_check_modules(GPUJ2K_ESPEAK_NG QUIET IMPORTED_TARGET espeak-ng)
endif()
if(TARGET PkgConfig::GPUJ2K_ESPEAK_NG)
  set(GPUJ2K_ESPEAK_NG_TARGET PkgConfig::GPUJ2K_ESPEAK_NG)
else()
  # No pkg-config (or no .pc file): look for the header and the library directly.
  find_path(GPUJ2K_ESPEAK_NG_INCLUDE_DIR espeak-ng/espeak_ng.h)
  find_library(GPUJ2K_ESPEAK_NG_LIBRARY espeak-ng)
  if(NOT GPUJ2K_ESPEAK_NG_INCLUDE_DIR OR NOT GPUJ2K_ESPEAK_NG_LIBRARY)
    message(FATAL_ERROR "espeak-ng not found (the performer's text to speech needs it): "
                        "install libespeak-ng-dev (Debian/Ubuntu) or set CMAKE_PREFIX_PATH")
  endif()
  add_library(gpuj2k_espeak_ng UNKNOWN IMPORTED)
  set_target_properties(gpuj2k_espeak_ng PROPERTIES
    IMPORTED_LOCATION "${GPUJ2K_ESPEAK_NG_LIBRARY}"
    INTERFACE_INCLUDE_DIRECTORIES "${GPUJ2K_ESPEAK_NG_INCLUDE_DIR}")
  set(GPUJ2K_ESPEAK_NG_TARGET gpuj2k_espeak_ng)
endif()

target_sources(gpuj2k_performer PRIVATE
  ${CMAKE_CURRENT_LIST_DIR}/src/speech.cpp
  ${CMAKE_CURRENT_LIST_DIR}/src/utf8_scan.cpp
  ${CMAKE_CURRENT_LIST_DIR}/src/espeak_engine.cpp
  ${CMAKE_CURRENT_LIST_DIR}/src/espeak_tts.cpp
  ${CMAKE_CURRENT_LIST_DIR}/src/espeak_visemes.cpp
  ${CMAKE_CURRENT_LIST_DIR}/src/speech_visemes.cpp
  ${CMAKE_CURRENT_LIST_DIR}/src/wav.cpp)
# PRIVATE: no espeak-ng type appears in a performer header, so nothing that uses the performer
# compiles against espeak-ng; it is only linked.
target_link_libraries(gpuj2k_performer PRIVATE ${GPUJ2K_ESPEAK_NG_TARGET})
