# Install rules: headers, the layer libraries and a package config, so that an installed
# chasles is used with find_package(chasles) and target_link_libraries(app chasles::chasles)
# (docs/cpp.md). Included from the top-level CMakeLists.txt after src/.
include(CMakePackageConfigHelpers)
set(CHASLES_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/chasles)

install(DIRECTORY ${PROJECT_SOURCE_DIR}/include/chasles
        DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}
        FILES_MATCHING PATTERN "*.h")
install(EXPORT chaslesTargets NAMESPACE chasles:: DESTINATION ${CHASLES_CMAKE_DIR})

configure_package_config_file(${CMAKE_CURRENT_LIST_DIR}/chaslesConfig.cmake.in
  ${PROJECT_BINARY_DIR}/chaslesConfig.cmake INSTALL_DESTINATION ${CHASLES_CMAKE_DIR})
# 0.x: a minor version may break the API.
write_basic_package_version_file(${PROJECT_BINARY_DIR}/chaslesConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/chaslesConfig.cmake
              ${PROJECT_BINARY_DIR}/chaslesConfigVersion.cmake
        DESTINATION ${CHASLES_CMAKE_DIR})
