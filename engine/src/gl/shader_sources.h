// GLSL sources embedded at build time from shaders/ (see cmake/EmbedShaders.cmake).
#pragma once

#include <string_view>
#include <vector>

namespace shadow::gpu {

/// One file of shaders/: its file name and text.
struct ShaderSource {
    const char* name;
    const char* text;
};

/// Every file of shaders/, embedded at build time.
const std::vector<ShaderSource>& embeddedShaderSources();

/// The text of the embedded shader file `name`, or null.
const char* findShaderSource(std::string_view name);

}  // namespace shadow::gpu
