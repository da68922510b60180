# Runs the embedding host (tests/embed) one way, as a test (cmake -P):
#   MODE=package       installs the main build (BUILD_DIR) into WORK_DIR/prefix, then builds the
#                      host against it with find_package; a fresh host build every run.
#   MODE=subdirectory  builds the host with add_subdirectory(SOURCE_DIR) in WORK_DIR/host, which
#                      compiles the module's libraries with its subproject defaults; the build
#                      directory is kept, so a second run rebuilds only what changed.
# Also: GENERATOR, CXX_COMPILER, C_COMPILER, BUILD_TYPE (the main build's, package mode only:
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
  run("configuring the host" ${configure} -DCMAKE_PREFIX_PATH=${WORK_DIR}/prefix -DCMAKE_BUILD_TYPE=${BUILD_TYPE})
elseif(MODE STREQUAL "subdirectory")
  # The module's project() enables C as well.
  run("configuring the host" ${configure} -DCMAKE_C_COMPILER=${C_COMPILER} -DSHADOW_ENGINE_SOURCE_DIR=${SOURCE_DIR})
else()
  message(FATAL_ERROR "run_embed_test.cmake: MODE must be package or subdirectory")
endif()
run("building the host" ${CMAKE_COMMAND} --build ${host_dir} --parallel ${jobs})
run("running the host" ${host_dir}/embed_host)
