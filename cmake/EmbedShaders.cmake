# embed_shaders(OUTPUT out.cpp FILES a.glsl b.glsl ...)
# Generates a C++ source defining shadow::gpu::embeddedShaderSources(): every file's name and
# text, so programs need no shader files at run time. Regenerated when a shader changes.
set(_EMBED_SHADERS_SCRIPT ${CMAKE_CURRENT_LIST_DIR}/EmbedShadersScript.cmake)

function(embed_shaders)
  cmake_parse_arguments(ARG "" "OUTPUT" "FILES" ${ARGN})
  add_custom_command(
    OUTPUT ${ARG_OUTPUT}
    COMMAND ${CMAKE_COMMAND} -DOUTPUT=${ARG_OUTPUT} "-DFILES=${ARG_FILES}" -P ${_EMBED_SHADERS_SCRIPT}
    DEPENDS ${ARG_FILES} ${_EMBED_SHADERS_SCRIPT}
    COMMENT "Embedding shaders"
    VERBATIM)
endfunction()
