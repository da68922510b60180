// Thin RAII owners of GL objects. Move-only; the destructor deletes the object. Every object
// gets a label (`Shadow/sun/array`) so GPU debuggers and error messages can name it.
#pragma once

#include "gl/gl_api.h"

#include <cstddef>
#include <cstdint>
#include <string_view>
#include <utility>

namespace shadow::gpu {

/// Records that the engine deleted `name`, a GL object of kind `identifier` (GL_TEXTURE,
/// GL_BUFFER, ...), on this thread. A state guard alive across the deletion then leaves it
/// unbound instead of binding it back: a host that had bound it (a shadow map it sampled) gets
/// what GL itself leaves after a delete, even when the name was made anew since. Never throws,
/// never allocates (a fixed ring of the last `kDeletionsRemembered`).
void noteDeleted(GLenum identifier, GLuint name) noexcept;
/// How many deletions this thread has noted so far: a guard's mark for `deletedSince`.
[[nodiscard]] std::uint64_t deletionCount() noexcept;
/// Whether `name` of kind `identifier` was deleted after `mark` (a `deletionCount`). False when
/// more than `kDeletionsRemembered` deletions followed the mark and it was not among the last
/// ones: the caller then relies on glIs* alone.
[[nodiscard]] bool deletedSince(GLenum identifier, GLuint name, std::uint64_t mark) noexcept;
/// Deletions the record holds.
inline constexpr std::size_t kDeletionsRemembered = 256;

/// Owns one GL name of kind `Kind`.
template <typename Kind>
class Object {
public:
    Object() = default;
    explicit Object(GLuint name) : name_(name) {}
    ~Object() { reset(); }
    Object(const Object&) = delete;
    Object& operator=(const Object&) = delete;
    Object(Object&& o) noexcept : name_(std::exchange(o.name_, 0)) {}
    Object& operator=(Object&& o) noexcept {
        if (this != &o) {
            reset();
            name_ = std::exchange(o.name_, 0);
        }
        return *this;
    }

    [[nodiscard]] GLuint get() const { return name_; }
    explicit operator bool() const { return name_ != 0; }
    void reset() {
        if (name_ != 0) {
            Kind::destroy(name_);
            noteDeleted(Kind::kIdentifier, name_);
        }
        name_ = 0;
    }
    /// Names the object for debuggers (glObjectLabel).
    void label(std::string_view text) const {
        if (name_ != 0) {
            gl.ObjectLabel(Kind::kIdentifier, name_, static_cast<GLsizei>(text.size()), text.data());
        }
    }

private:
    GLuint name_ = 0;
};

struct BufferKind {
    static constexpr GLenum kIdentifier = GL_BUFFER;
    static void destroy(GLuint n) { gl.DeleteBuffers(1, &n); }
};
struct TextureKind {
    static constexpr GLenum kIdentifier = GL_TEXTURE;
    static void destroy(GLuint n) { gl.DeleteTextures(1, &n); }
};
struct FramebufferKind {
    static constexpr GLenum kIdentifier = GL_FRAMEBUFFER;
    static void destroy(GLuint n) { gl.DeleteFramebuffers(1, &n); }
};
struct VertexArrayKind {
    static constexpr GLenum kIdentifier = GL_VERTEX_ARRAY;
    static void destroy(GLuint n) { gl.DeleteVertexArrays(1, &n); }
};
struct SamplerKind {
    static constexpr GLenum kIdentifier = GL_SAMPLER;
    static void destroy(GLuint n) { gl.DeleteSamplers(1, &n); }
};
struct ProgramKind {
    static constexpr GLenum kIdentifier = GL_PROGRAM;
    static void destroy(GLuint n) { gl.DeleteProgram(n); }
};

using Buffer = Object<BufferKind>;
using Texture = Object<TextureKind>;
using Framebuffer = Object<FramebufferKind>;
using VertexArray = Object<VertexArrayKind>;
using Program = Object<ProgramKind>;
using Sampler = Object<SamplerKind>;

/// Makes an immutable buffer holding `bytes` bytes of `data` (may be null), labelled.
Buffer makeBuffer(std::string_view label, GLsizeiptr bytes, const void* data, GLbitfield flags);
/// Makes a texture of `target` with immutable storage left to the caller, labelled.
Texture makeTexture(std::string_view label, GLenum target);
/// Makes a screen-space target: a 2D texture (a 2D array of `layers` when > 0) of one level of
/// `format`, `w` x `h`, read texel by texel (nearest filters: an integer texture is incomplete,
/// and reads 0, with a linear one), labelled.
Texture makeScreenTarget(std::string_view label, GLenum format, int w, int h, int layers = 0);
/// Makes a framebuffer, labelled.
Framebuffer makeFramebuffer(std::string_view label);
/// Makes a vertex array, labelled: with no attribute, what a full-screen triangle made from
/// gl_VertexID is drawn with.
VertexArray makeVertexArray(std::string_view label);

/// The name of GL error code `e` ("GL_INVALID_ENUM", ...).
[[nodiscard]] const char* glErrorName(GLenum e);

/// Throws `GlError` naming `where` and the error if the GL error flag is set.
void checkGlError(std::string_view where);

}  // namespace shadow::gpu
