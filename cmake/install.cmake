# `cmake --install`: the codec library (libgpuj2k.so, its public headers gpuj2k/*.h), the
# OpenImageIO reader module it loads, the tools, a CMake package (find_package(gpuj2k CONFIG),
# target gpuj2k::gpuj2k) and a pkg-config file (gpuj2k.pc). Programs find the library and the module
# through their RUNPATH, $ORIGIN/../lib.
include(CMakePackageConfigHelpers)

set(GPUJ2K_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/gpuj2k)
install(TARGETS gpuj2k EXPORT gpuj2kTargets
  LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
  INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/gpuj2k/include/gpuj2k DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(TARGETS gpuj2k_imageio_oiio LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR})
set(GPUJ2K_TOOLS j2kenc dwtool imgpsnr gentestimage)
if(TARGET performer)
  list(APPEND GPUJ2K_TOOLS performer)
endif()
foreach(tool IN LISTS GPUJ2K_TOOLS)
  if(TARGET ${tool})
    set_target_properties(${tool} PROPERTIES INSTALL_RPATH "$ORIGIN/../${CMAKE_INSTALL_LIBDIR}")
    install(TARGETS ${tool} RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
  endif()
endforeach()

install(EXPORT gpuj2kTargets NAMESPACE gpuj2k:: DESTINATION ${GPUJ2K_CMAKE_DIR})
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/gpuj2kConfig.cmake.in
  ${PROJECT_BINARY_DIR}/gpuj2kConfig.cmake INSTALL_DESTINATION ${GPUJ2K_CMAKE_DIR})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/gpuj2kConfigVersion.cmake COMPATIBILITY SameMajorVersion)
install(FILES ${PROJECT_BINARY_DIR}/gpuj2kConfig.cmake ${PROJECT_BINARY_DIR}/gpuj2kConfigVersion.cmake
  DESTINATION ${GPUJ2K_CMAKE_DIR})

# The .pc file names its prefix relative to itself, so the installed tree can move.
file(RELATIVE_PATH GPUJ2K_PC_PREFIX "${CMAKE_INSTALL_FULL_LIBDIR}/pkgconfig" "${CMAKE_INSTALL_PREFIX}")
configure_file(${PROJECT_SOURCE_DIR}/cmake/gpuj2k.pc.in ${PROJECT_BINARY_DIR}/gpuj2k.pc @ONLY)
install(FILES ${PROJECT_BINARY_DIR}/gpuj2k.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)
