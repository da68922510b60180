# shadow_warnings(TARGET): the project's warning set on one of its own targets.
# Third-party headers come in as SYSTEM includes, so -Werror only judges our code.
function(shadow_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow=local
                                           -Wnon-virtual-dtor -Wcast-align -Wnull-dereference)
  if(SHADOW_WERROR)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
endfunction()
