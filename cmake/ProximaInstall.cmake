# Installation and the CMake package: find_package(proxima CONFIG REQUIRED) then link
# proxima::proxima.
include(CMakePackageConfigHelpers)

install(TARGETS proxima EXPORT proximaTargets
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
  LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
  RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR}
  INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(DIRECTORY "${PROJECT_SOURCE_DIR}/include/proxima" DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}
  FILES_MATCHING PATTERN "*.hpp")
install(FILES "${PROJECT_BINARY_DIR}/generated/include/proxima/core/config.hpp"
  DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/proxima/core)

set(PROXIMA_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/proxima)
install(EXPORT proximaTargets NAMESPACE proxima:: DESTINATION ${PROXIMA_CMAKE_DIR})
configure_package_config_file("${PROJECT_SOURCE_DIR}/cmake/proximaConfig.cmake.in"
  "${PROJECT_BINARY_DIR}/proximaConfig.cmake" INSTALL_DESTINATION ${PROXIMA_CMAKE_DIR})
write_basic_package_version_file("${PROJECT_BINARY_DIR}/proximaConfigVersion.cmake"
  COMPATIBILITY SameMinorVersion)
install(FILES "${PROJECT_BINARY_DIR}/proximaConfig.cmake" "${PROJECT_BINARY_DIR}/proximaConfigVersion.cmake"
  DESTINATION ${PROXIMA_CMAKE_DIR})
