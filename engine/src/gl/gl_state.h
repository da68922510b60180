// Good manners towards a host that owns the GL context: the state the engine's passes change,
// captured before a public call and put back after it; errors the host left pending, told
// apart from the engine's own; and a clear error for a call made before `loadGl`.
#pragma once

#include "gl/gl_api.h"

#include <shadow/stats.h>

#include <array>
#include <cstddef>
#include <span>
#include <string>
#include <string_view>

namespace shadow::gpu {

/// Throws `GlError` naming `who` when `loadGl` has not run (every entry point would be null).
void requireLoaded(std::string_view who);

/// Reads and clears every error pending in the context; "" when there is none, else the codes
/// (e.g. "GL_INVALID_ENUM"), comma-separated. Call before the engine's own GL calls, so that
/// an error the host left behind is reported as the host's and not thrown as the engine's.
[[nodiscard]] std::string takePendingErrors();

/// `takePendingErrors`, and a `HostGlError` warning in `stats` naming the engine call `call`
/// when there was one.
void reportHostGlErrors(std::string_view call, FrameStats& stats);

/// The pieces of GL state the shadow system and the renderer change. Texture units and
/// uniform-buffer binding points are captured only for the ones named.
struct GlState {
    GLint drawFramebuffer = 0;
    GLint readFramebuffer = 0;
    GLint program = 0;
    GLint vertexArray = 0;
    std::array<GLint, 4> viewport{};
    std::array<GLint, 4> scissorBox{};
    GLboolean scissorTest = GL_FALSE;
    GLboolean depthTest = GL_FALSE;
    GLint depthFunc = GL_LESS;
    GLboolean depthMask = GL_TRUE;
    GLboolean cullFace = GL_FALSE;
    GLint cullFaceMode = GL_BACK;
    GLint frontFace = GL_CCW;
    GLboolean polygonOffsetFill = GL_FALSE;
    std::array<GLboolean, 8> blend{};  ///< per draw buffer
    std::array<GLint, 4> blendFunc{};  ///< src rgb, dst rgb, src alpha, dst alpha
    std::array<GLboolean, 4> colorMask{};
    GLint packAlignment = 4;
    GLint packRowLength = 0;
    GLint pixelPackBuffer = 0;
    GLint activeTexture = GL_TEXTURE0;
    GLint uniformBuffer = 0;  ///< the generic GL_UNIFORM_BUFFER binding
    struct Unit {
        GLint unit = 0;
        GLint texture2D = 0;
        GLint texture2DArray = 0;
        GLint sampler = 0;
        bool operator==(const Unit&) const = default;
    };
    /// The first `unitCount` are captured (fixed storage: capturing allocates nothing).
    std::array<Unit, 32> units{};
    std::size_t unitCount = 0;
    struct UniformBinding {
        GLint index = 0;
        GLint buffer = 0;
        GLint64 start = 0;
        GLint64 size = 0;
        bool operator==(const UniformBinding&) const = default;
    };
    std::array<UniformBinding, 4> uniformBindings{};
    std::size_t uniformBindingCount = 0;
    struct ImageBinding {
        GLint unit = 0;
        GLint texture = 0;
        GLint level = 0;
        GLboolean layered = GL_FALSE;
        GLint layer = 0;
        GLint access = GL_READ_ONLY;
        GLint format = GL_R8;
        bool operator==(const ImageBinding&) const = default;
    };
    std::array<ImageBinding, 4> images{};
    std::size_t imageCount = 0;

    bool operator==(const GlState&) const = default;
};

/// Reads the state, with the texture units `units` (at most 32), the uniform-buffer binding
/// points `uniformBindings` (at most 4) and the image units `imageUnits` (at most 4); the ones
/// beyond are not captured.
[[nodiscard]] GlState captureGlState(std::span<const GLint> units, std::span<const GLint> uniformBindings,
                                     std::span<const GLint> imageUnits = {});
/// Puts `state` back.
void restoreGlState(const GlState& state);

/// The raster state every pass of the engine assumes, whatever the host left: scissor test off,
/// colour writes on, counter-clockwise front faces, no polygon offset, no blending. Each pass
/// sets the rest (framebuffer, viewport, depth, culling) itself. Every piece is in `GlState`.
void setPassDefaults();

/// Pixel-pack state for reading back into client memory, whatever the host left: no pack buffer,
/// rows tightly packed (alignment 1, row length 0). Every piece is in `GlState`.
void setReadbackDefaults();

/// Captures on construction, restores on destruction (also when the scope is left by a throw).
class GlStateGuard {
public:
    GlStateGuard(std::span<const GLint> units, std::span<const GLint> uniformBindings,
                 std::span<const GLint> imageUnits = {})
        : saved_(captureGlState(units, uniformBindings, imageUnits)) {}
    ~GlStateGuard() { restoreGlState(saved_); }
    GlStateGuard(const GlStateGuard&) = delete;
    GlStateGuard& operator=(const GlStateGuard&) = delete;

private:
    GlState saved_;
};

}  // namespace shadow::gpu
