// GL object names and enums as typed values in the public API, without GL headers: a texture
// cannot be passed where a buffer is due, and an index type is one of three, not any number.
// Each holds the GL name (`name`, 0 for none) the game binds or hands over.
#pragma once

#include <compare>

namespace shadow {

/// A GL texture name (glCreateTextures / glGenTextures); 0: none.
struct GlTexture {
    unsigned name = 0;  ///< the GL name
    /// True when it names a texture.
    explicit operator bool() const { return name != 0; }
    auto operator<=>(const GlTexture&) const = default;
};

/// A GL buffer name; 0: none.
struct GlBuffer {
    unsigned name = 0;  ///< the GL name
    /// True when it names a buffer.
    explicit operator bool() const { return name != 0; }
    auto operator<=>(const GlBuffer&) const = default;
};

/// A GL sampler object name; 0: none (a unit then samples with its texture's own parameters).
struct GlSampler {
    unsigned name = 0;  ///< the GL name
    /// True when it names a sampler.
    explicit operator bool() const { return name != 0; }
    auto operator<=>(const GlSampler&) const = default;
};

/// A GL vertex array object name; 0: none.
struct GlVertexArray {
    unsigned name = 0;  ///< the GL name
    /// True when it names a vertex array.
    explicit operator bool() const { return name != 0; }
    auto operator<=>(const GlVertexArray&) const = default;
};

/// A GL program name; 0: none.
struct GlProgram {
    unsigned name = 0;  ///< the GL name
    /// True when it names a program.
    explicit operator bool() const { return name != 0; }
    auto operator<=>(const GlProgram&) const = default;
};

/// The type of an element buffer's indices; the values are GL's enums.
enum class IndexType : unsigned {
    U8 = 0x1401,   ///< GL_UNSIGNED_BYTE
    U16 = 0x1403,  ///< GL_UNSIGNED_SHORT
    U32 = 0x1405,  ///< GL_UNSIGNED_INT
};

}  // namespace shadow
