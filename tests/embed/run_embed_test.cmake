# Runs the embedding host (tests/embed) one way, as a test (cmake -P):
#   MODE=package       installs the main build (BUILD_DIR) into WORK_DIR/prefix, then builds the
#                      host against it with find_package; a fresh host build every run.
#   MODE=subdirectory  builds the host with add_subdirectory(SOURCE_DIR) in WORK_DIR/host, which
#                      compiles the module's libraries with its subproject defaults; the build
#                      directory is kept, so a second run rebuilds only what changed.
#                      With CONFIGURE_ONLY=ON it stops after configuring: the checks the host's
#                      CMakeLists.txt makes of the module as a subproject, without compiling it.
# Also: GENERATOR, CXX_COMPILER, C_COMPILER, NM (package mode: the declarations check),
# BUILD_TYPE (the main build's, package mode only:
# subdirectory mode leaves it empty, and the host checks the module does not set it).
# Builds serially unless CMAKE_BUILD_PARALLEL_LEVEL is set in the environment.
foreach(var MODE SOURCE_DIR BUILD_DIR WORK_DIR GENERATOR CXX_COMPILER C_COMPILER)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "run_embed_test.cmake: ${var} is not set")
  endif()
endforeach()

function(run step)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "embed (${MODE}): ${step} failed (${rc})")
  endif()
endfunction()

set(jobs 1)
if(DEFINED ENV{CMAKE_BUILD_PARALLEL_LEVEL})
  set(jobs $ENV{CMAKE_BUILD_PARALLEL_LEVEL})
endif()
set(host_dir ${WORK_DIR}/host)
set(configure ${CMAKE_COMMAND} -S ${SOURCE_DIR}/tests/embed -B ${host_dir} -G ${GENERATOR}
    -DCMAKE_CXX_COMPILER=${CXX_COMPILER} -DSHADOW_EMBED_MODE=${MODE})

if(MODE STREQUAL "package")
  file(REMOVE_RECURSE ${WORK_DIR})
  run("installing the main build" ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${WORK_DIR}/prefix)
  # Every free function an installed header declares links from the installed package: it is
  # defined in one of the installed libraries (a header whose library is not installed, such as
  # the EGL backend's, is not installed either). Declarations are read as the headers write
  # them: at the start of a line, `name(` before any comment, not inline, constexpr or a template
  # (nor a function of a header GLSL shares, defined in place behind an SG_ macro: inline in C++).
  if(NOT NM)
    message(FATAL_ERROR "run_embed_test.cmake: NM is not set")
  endif()
  file(GLOB installed_headers ${WORK_DIR}/prefix/include/shadow/*.h)
  file(GLOB_RECURSE installed_libraries ${WORK_DIR}/prefix/*.a)
  execute_process(COMMAND ${NM} -C --defined-only ${installed_libraries} OUTPUT_VARIABLE defined RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "embed (${MODE}): nm failed (${rc})")
  endif()
  set(declared 0)
  foreach(header IN LISTS installed_headers)
    file(STRINGS ${header} lines REGEX "^[A-Za-z[][^/]*[ *&][a-z][A-Za-z0-9_]*\\(")
    foreach(line IN LISTS lines)
      if(line MATCHES "^(inline|constexpr|template|static|static_assert|struct|class|enum|using|namespace)[ <(]"
         OR line MATCHES "^\\[\\[nodiscard\\]\\] (constexpr|inline) " OR line MATCHES "{$" OR line MATCHES "^SG_[A-Z_]+ ")
        continue()
      endif()
      string(REGEX MATCH "([a-z][A-Za-z0-9_]*)\\(" name "${line}")
      set(name ${CMAKE_MATCH_1})
      math(EXPR declared "${declared} + 1")
      if(NOT defined MATCHES " shadow::([a-z]+::)?${name}(\\(|\\[abi:)")
        get_filename_component(header_name ${header} NAME)
        message(FATAL_ERROR "embed (${MODE}): shadow/${header_name} declares ${name}, "
                            "which no installed library defines")
      endif()
    endforeach()
  endforeach()
  if(declared LESS 10)
    message(FATAL_ERROR "embed (${MODE}): found only ${declared} declarations in the installed headers")
  endif()
  message(STATUS "embed (${MODE}): the ${declared} functions the installed headers declare are all defined")
  run("configuring the host" ${configure} -DCMAKE_PREFIX_PATH=${WORK_DIR}/prefix -DCMAKE_BUILD_TYPE=${BUILD_TYPE})
elseif(MODE STREQUAL "subdirectory")
  # The module's project() enables C as well.
  run("configuring the host" ${configure} -DCMAKE_C_COMPILER=${C_COMPILER} -DSHADOW_ENGINE_SOURCE_DIR=${SOURCE_DIR})
else()
  message(FATAL_ERROR "run_embed_test.cmake: MODE must be package or subdirectory")
endif()
if(CONFIGURE_ONLY)
  return()
endif()
run("building the host" ${CMAKE_COMMAND} --build ${host_dir} --parallel ${jobs})
run("running the host" ${host_dir}/embed_host)
