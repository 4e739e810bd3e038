# Install rules: public headers, every module library (recorded by glcollide_module() in the global
# property GLCOLLIDE_MODULE_TARGETS, so a new module is installed without touching this file), the
# CLI, and a relocatable CMake package: find_package(glcollide) gives glcollide::glcollide (the
# engine) and glcollide::<module> for the others. Shaders are embedded in glcollide::gl, so nothing
# else is installed. Included from the top-level CMakeLists.txt after add_subdirectory(src).
include(CMakePackageConfigHelpers)

set(GLCOLLIDE_INSTALL_CMAKEDIR ${CMAKE_INSTALL_LIBDIR}/cmake/glcollide
  CACHE STRING "Where glcollideConfig.cmake is installed, relative to the prefix")

install(DIRECTORY ${PROJECT_SOURCE_DIR}/include/glcollide
  DESTINATION ${CMAKE_INSTALL_INCLUDEDIR} COMPONENT glcollide_development
  FILES_MATCHING PATTERN "*.hpp")

get_property(_glcollide_modules GLOBAL PROPERTY GLCOLLIDE_MODULE_TARGETS)
install(TARGETS ${_glcollide_modules} EXPORT glcollideTargets
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT glcollide_development
  LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT glcollide_runtime
  RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR} COMPONENT glcollide_runtime)
if(TARGET glcollide)
  install(TARGETS glcollide RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR} COMPONENT glcollide_runtime)
endif()

install(EXPORT glcollideTargets NAMESPACE glcollide:: DESTINATION ${GLCOLLIDE_INSTALL_CMAKEDIR}
  COMPONENT glcollide_development)
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/glcollideConfig.cmake.in
  ${PROJECT_BINARY_DIR}/glcollideConfig.cmake INSTALL_DESTINATION ${GLCOLLIDE_INSTALL_CMAKEDIR})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/glcollideConfigVersion.cmake
  VERSION ${PROJECT_VERSION} COMPATIBILITY SameMajorVersion)
install(FILES ${PROJECT_BINARY_DIR}/glcollideConfig.cmake ${PROJECT_BINARY_DIR}/glcollideConfigVersion.cmake
  DESTINATION ${GLCOLLIDE_INSTALL_CMAKEDIR} COMPONENT glcollide_development)
