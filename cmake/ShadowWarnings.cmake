# shadow_warnings(TARGET): the project's warning set on one of its own targets.
# Third-party headers come in as SYSTEM includes, so -Werror only judges our code.
function(shadow_warnings target)
  # -Wshadow=local is GCC's; clang (the sanitizer and fuzzing build) would warn of it per file.
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic $<$<CXX_COMPILER_ID:GNU>:-Wshadow=local>
                                           -Wnon-virtual-dtor -Wcast-align -Wnull-dereference)
  if(SHADOW_WERROR)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
endfunction()

# shadow_light_optimisation(target): -O1 in an optimised build, for code whose own work is small
# beside what it calls: the test programs (comparisons of images, brute-force references) and
# the command-line front ends (parsing, writing files), whose rendering, tracing and metrics run
# in the libraries, which keep the build type's optimisation. Compiles in about half to two
# thirds of the time of -O3 (shadow_compare.cpp 17.7 s -> 11.7, shadow_render.cpp 14.0 -> 9.9).
function(shadow_light_optimisation target)
  target_compile_options(${target} PRIVATE $<$<CONFIG:Release,RelWithDebInfo,MinSizeRel>:-O1>)
endfunction()
