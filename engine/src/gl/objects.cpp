#include "gl/objects.h"

#include <shadow/context.h>

#include <algorithm>
#include <array>
#include <string>
#include <utility>

namespace shadow::gpu {
namespace {

/// The last deletions of this thread (GL contexts are current per thread).
struct Deletions {
    std::array<std::pair<GLenum, GLuint>, kDeletionsRemembered> ring{};
    std::uint64_t count = 0;
};
thread_local Deletions tDeletions;

}  // namespace

void noteDeleted(GLenum identifier, GLuint name) noexcept {
    Deletions& d = tDeletions;
    d.ring[d.count % d.ring.size()] = {identifier, name};
    ++d.count;
}

std::uint64_t deletionCount() noexcept { return tDeletions.count; }

bool deletedSince(GLenum identifier, GLuint name, std::uint64_t mark) noexcept {
    const Deletions& d = tDeletions;
    if (mark >= d.count) return false;
    const std::uint64_t first = d.count - std::min<std::uint64_t>(d.count - mark, d.ring.size());
    for (std::uint64_t i = first; i < d.count; ++i) {
        if (d.ring[i % d.ring.size()] == std::pair{identifier, name}) return true;
    }
    return false;
}

Buffer makeBuffer(std::string_view label, GLsizeiptr bytes, const void* data, GLbitfield flags) {
    GLuint name = 0;
    gl.CreateBuffers(1, &name);
    Buffer b(name);
    // Zero-sized storage is an error in GL; keep one byte so empty meshes stay valid objects.
    gl.NamedBufferStorage(name, bytes > 0 ? bytes : 1, bytes > 0 ? data : nullptr, flags);
    b.label(label);
    return b;
}

namespace {

/// A new object of kind `Object`, its name from `create(&name)`, labelled `label`.
template <typename Object, typename Create>
Object makeLabelled(std::string_view label, Create create) {
    GLuint name = 0;
    create(&name);
    Object o(name);
    o.label(label);
    return o;
}

}  // namespace

Texture makeTexture(std::string_view label, GLenum target) {
    return makeLabelled<Texture>(label, [target](GLuint* n) { gl.CreateTextures(target, 1, n); });
}

Texture makeScreenTarget(std::string_view label, GLenum format, int w, int h, int layers) {
    Texture t = makeTexture(label, layers > 0 ? GL_TEXTURE_2D_ARRAY : GL_TEXTURE_2D);
    if (layers > 0) {
        gl.TextureStorage3D(t.get(), 1, format, w, h, layers);
    } else {
        gl.TextureStorage2D(t.get(), 1, format, w, h);
    }
    gl.TextureParameteri(t.get(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    gl.TextureParameteri(t.get(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    return t;
}

Framebuffer makeFramebuffer(std::string_view label) {
    return makeLabelled<Framebuffer>(label, [](GLuint* n) { gl.CreateFramebuffers(1, n); });
}

VertexArray makeVertexArray(std::string_view label) {
    return makeLabelled<VertexArray>(label, [](GLuint* n) { gl.CreateVertexArrays(1, n); });
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
