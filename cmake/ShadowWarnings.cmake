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
