# Install rules and the CMake package (find_package(shadow_engine CONFIG)), included by the
# top-level CMakeLists.txt when SHADOW_INSTALL is on. Layout under the prefix:
#   lib/                            libshadow_core.a, libshadow_engine.a, ... (static)
#   include/shadow/                 the public headers of the installed libraries
#   share/shadow_engine/shaders/    the GLSL sources and the C++/GLSL shared headers
#   lib/cmake/shadow_engine/        shadow_engineConfig.cmake, ...ConfigVersion.cmake, targets
#
# Targets (namespace shadow::): scene (ECS, scene, glTF; the library shadow_core) and engine
# (GL shadow subsystem and renderer; shadow_engine) always; the components osmesa (headless
# context backend) and reference (Embree tracer) when built and asked for.
#
# Static, not shared: a game ships one binary, the C++ interface of a 0.x library has no stable
# ABI to share across versions (plain structs, inline code), and a static library needs no
# rpath. The cost is that private dependencies reach the game's link line; the config finds
# them again (TinyGLTF, OpenEXR, stb, Threads; OSMesa and Embree only for their components).
#
# GLSL under share/ and not include/: it is data a game's shader loader reads (or its build
# embeds), not C++ for the game's include path. The two headers C++ and GLSL share are public
# headers of shadow::engine (include/shadow/) and stand beside the GLSL as well.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(SHADOW_INSTALL_CMAKEDIR ${CMAKE_INSTALL_LIBDIR}/cmake/shadow_engine)
set(SHADOW_INSTALL_SHADERDIR ${CMAKE_INSTALL_DATADIR}/shadow_engine/shaders)

# shadow_install_targets(STEM TARGET...): the targets, their headers and STEMTargets.cmake.
function(shadow_install_targets stem)
  install(TARGETS ${ARGN} EXPORT ${stem}
          ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
          FILE_SET HEADERS DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
  install(EXPORT ${stem} FILE ${stem}Targets.cmake NAMESPACE shadow:: DESTINATION ${SHADOW_INSTALL_CMAKEDIR})
endfunction()

shadow_install_targets(shadow_engine shadow_core shadow_engine)
# Components: shadow_engine_<component>Targets.cmake each.
set(SHADOW_INSTALLED_COMPONENTS "")
if(TARGET shadow_osmesa)
  shadow_install_targets(shadow_engine_osmesa shadow_osmesa)
  list(APPEND SHADOW_INSTALLED_COMPONENTS osmesa)
endif()
if(TARGET shadow_reference_lib)
  shadow_install_targets(shadow_engine_reference shadow_reference_lib)
  list(APPEND SHADOW_INSTALLED_COMPONENTS reference)
endif()

install(DIRECTORY ${PROJECT_SOURCE_DIR}/shaders/ DESTINATION ${SHADOW_INSTALL_SHADERDIR}
        FILES_MATCHING PATTERN "*.glsl" PATTERN "README.md")
# Beside the GLSL too, so that the folder compiles by `#include` on its own.
install(FILES ${PROJECT_SOURCE_DIR}/engine/include/shadow/shared_constants.h
              ${PROJECT_SOURCE_DIR}/engine/include/shadow/gpu_structs.h
              ${PROJECT_SOURCE_DIR}/engine/include/shadow/tone_map.h DESTINATION ${SHADOW_INSTALL_SHADERDIR})

configure_package_config_file(${CMAKE_CURRENT_LIST_DIR}/shadow_engineConfig.cmake.in
  ${PROJECT_BINARY_DIR}/shadow_engineConfig.cmake
  INSTALL_DESTINATION ${SHADOW_INSTALL_CMAKEDIR}
  PATH_VARS SHADOW_INSTALL_SHADERDIR)
# 0.x: a minor release may break the interface (Semantic Versioning, item 4), so 0.1.x satisfies
# a request for 0.1 but 0.2 does not; SameMajorVersion would accept any 0.y for 0.1.
write_basic_package_version_file(${PROJECT_BINARY_DIR}/shadow_engineConfigVersion.cmake
  VERSION ${PROJECT_VERSION} COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/shadow_engineConfig.cmake ${PROJECT_BINARY_DIR}/shadow_engineConfigVersion.cmake
        DESTINATION ${SHADOW_INSTALL_CMAKEDIR})
