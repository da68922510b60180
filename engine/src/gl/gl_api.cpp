#include "gl/gl_api.h"

#include <cstring>
#include <string>

namespace shadow {

gpu::Api gl;

Status loadGl(const GlProcLoader& loader) {
    if (!loader) return Error{ErrorCode::InvalidArgument, "loadGl: no getProcAddress given"};
    gpu::Api api;
    const char* missing = nullptr;
#define SHADOW_GL_LOAD(type, name)                         \
    api.name = reinterpret_cast<type>(loader("gl" #name)); \
    if (api.name == nullptr && missing == nullptr) missing = "gl" #name;
    SHADOW_GL_FUNCTIONS(SHADOW_GL_LOAD)
#undef SHADOW_GL_LOAD
    if (missing != nullptr) {
        return Error{ErrorCode::GlUnavailable, std::string("OpenGL entry point ") + missing +
                                                   " is missing: an OpenGL 4.5 core context is required"};
    }
    GLint major = 0;
    GLint minor = 0;
    api.GetIntegerv(GL_MAJOR_VERSION, &major);
    api.GetIntegerv(GL_MINOR_VERSION, &minor);
    if (major * 10 + minor < 45) {
        return Error{ErrorCode::GlUnavailable, "OpenGL " + std::to_string(major) + "." + std::to_string(minor) +
                                                   " context: OpenGL 4.5 core is required"};
    }
    gl = api;
    return Ok{};
}

GlInfo queryGlInfo() {
    GlInfo info;
    auto str = [](GLenum e) {
        const auto* s = reinterpret_cast<const char*>(gl.GetString(e));
        return s ? std::string(s) : std::string();
    };
    info.vendor = str(GL_VENDOR);
    info.renderer = str(GL_RENDERER);
    info.version = str(GL_VERSION);
    gl.GetIntegerv(GL_MAX_TEXTURE_SIZE, &info.maxTextureSize);
    gl.GetIntegerv(GL_MAX_ARRAY_TEXTURE_LAYERS, &info.maxArrayLayers);
    gl.GetIntegerv(GL_MAX_TEXTURE_IMAGE_UNITS, &info.maxTextureUnits);
    for (const char* cpu : {"llvmpipe", "softpipe", "swrast", "SWR", "lavapipe"}) {
        if (info.renderer.find(cpu) != std::string::npos) info.softwareRenderer = true;
    }
    return info;
}

}  // namespace shadow
