#include "gl/objects.h"

#include <shadow/context.h>

#include <string>

namespace shadow::gpu {

Buffer makeBuffer(std::string_view label, GLsizeiptr bytes, const void* data, GLbitfield flags) {
    GLuint name = 0;
    gl.CreateBuffers(1, &name);
    Buffer b(name);
    // Zero-sized storage is an error in GL; keep one byte so empty meshes stay valid objects.
    gl.NamedBufferStorage(name, bytes > 0 ? bytes : 1, bytes > 0 ? data : nullptr, flags);
    b.label(label);
    return b;
}

Texture makeTexture(std::string_view label, GLenum target) {
    GLuint name = 0;
    gl.CreateTextures(target, 1, &name);
    Texture t(name);
    t.label(label);
    return t;
}

Framebuffer makeFramebuffer(std::string_view label) {
    GLuint name = 0;
    gl.CreateFramebuffers(1, &name);
    Framebuffer f(name);
    f.label(label);
    return f;
}

const char* glErrorName(GLenum e) {
    switch (e) {
        case GL_INVALID_ENUM: return "GL_INVALID_ENUM";
        case GL_INVALID_VALUE: return "GL_INVALID_VALUE";
        case GL_INVALID_OPERATION: return "GL_INVALID_OPERATION";
        case GL_INVALID_FRAMEBUFFER_OPERATION: return "GL_INVALID_FRAMEBUFFER_OPERATION";
        case GL_OUT_OF_MEMORY: return "GL_OUT_OF_MEMORY";
        case GL_STACK_OVERFLOW: return "GL_STACK_OVERFLOW";
        case GL_STACK_UNDERFLOW: return "GL_STACK_UNDERFLOW";
        default: return "unknown GL error";
    }
}

void checkGlError(std::string_view where) {
    const GLenum e = gl.GetError();
    if (e == GL_NO_ERROR) return;
    std::string message = std::string(where) + ": " + glErrorName(e);
    // Drain the remaining flags so the next check reports only new errors.
    while (gl.GetError() != GL_NO_ERROR) {}
    throw GlError(message);
}

}  // namespace shadow::gpu
