// Good manners towards a host that owns the GL context: the state the engine's passes change,
// captured before a public call and put back after it; errors the host left pending, told
// apart from the engine's own; and a clear error for a call made before `loadGl`.
//
// What a pass relies on and therefore sets (setPassDefaults), and the guard puts back: the
// framebuffers, program, vertex array, viewport, scissor, depth test/function/mask/range, clip
// control, polygon mode, culling and front face, polygon offset, blending (enables, function,
// equation), colour mask, and every capability that would change what a pass writes when a
// host leaves it on (kPassOffCapabilities: depth clamp, rasterizer discard, stencil test, logic
// op, sRGB writes, primitive restart, the multisample coverage operations, polygon smoothing,
// user clip distances). Readbacks also set and restore every pixel-pack parameter and read
// colour clamping. Texture units (every target, and the sampler), uniform-buffer binding points
// and image units are captured for the ones a call names; the joint matrices' storage binding
// always. Left alone, because no pass depends
// on them: the stencil functions and masks (no framebuffer of the engine has stencil), the
// blend colour (no pass blends with a constant), line and point state (fill only), dithering,
// hints, the provoking vertex (no flat inputs), and conditional rendering or transform
// feedback a host left active (GL has no query for the former: a host must not leave either
// active across a call).
#pragma once

#include "gl/gl_api.h"
#include "gl/objects.h"

#include <shadow/stats.h>
#include <shadow/warnings.h>

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace shadow::gpu {

/// Throws `GlError` naming `who` when `loadGl` has not run (every entry point would be null).
void requireLoaded(std::string_view who);

/// Reads and clears every error pending in the context; "" when there is none, else the codes
/// (e.g. "GL_INVALID_ENUM"), comma-separated. Call before the engine's own GL calls, so that
/// an error the host left behind is reported as the host's and not thrown as the engine's.
[[nodiscard]] std::string takePendingErrors();

/// The one policy for an error the host left pending, applied by every public call that talks
/// to GL before its own first GL call: read it, clear it, and append a `HostGlError` warning
/// naming the call `call` to `warnings` (a `FrameStats::warnings`, or the pending warnings of an
/// object whose call has no `FrameStats`); never throw it. Appends nothing when `warnings`
/// already holds `limit` entries (an object's pending list that nobody reads stays bounded).
void reportHostGlErrors(std::string_view call, std::vector<Warning>& warnings, std::size_t limit = SIZE_MAX);

/// `reportHostGlErrors` into `stats.warnings`.
void reportHostGlErrors(std::string_view call, FrameStats& stats);

/// Most warnings an object keeps for calls without a `FrameStats` until they are read.
inline constexpr std::size_t kMaxPendingWarnings = 16;

/// Moves `pending` to the end of `to` (a frame's warnings), leaving `pending` empty with its
/// storage.
void movePendingWarnings(std::vector<Warning>& pending, std::vector<Warning>& to);

/// Every texture target a unit binds separately, and the query of each binding.
inline constexpr std::array<GLenum, 11> kTextureTargets{GL_TEXTURE_1D,
                                                        GL_TEXTURE_1D_ARRAY,
                                                        GL_TEXTURE_2D,
                                                        GL_TEXTURE_2D_ARRAY,
                                                        GL_TEXTURE_3D,
                                                        GL_TEXTURE_CUBE_MAP,
                                                        GL_TEXTURE_CUBE_MAP_ARRAY,
                                                        GL_TEXTURE_RECTANGLE,
                                                        GL_TEXTURE_BUFFER,
                                                        GL_TEXTURE_2D_MULTISAMPLE,
                                                        GL_TEXTURE_2D_MULTISAMPLE_ARRAY};
inline constexpr std::array<GLenum, 11> kTextureBindingQueries{GL_TEXTURE_BINDING_1D,
                                                               GL_TEXTURE_BINDING_1D_ARRAY,
                                                               GL_TEXTURE_BINDING_2D,
                                                               GL_TEXTURE_BINDING_2D_ARRAY,
                                                               GL_TEXTURE_BINDING_3D,
                                                               GL_TEXTURE_BINDING_CUBE_MAP,
                                                               GL_TEXTURE_BINDING_CUBE_MAP_ARRAY,
                                                               GL_TEXTURE_BINDING_RECTANGLE,
                                                               GL_TEXTURE_BINDING_BUFFER,
                                                               GL_TEXTURE_BINDING_2D_MULTISAMPLE,
                                                               GL_TEXTURE_BINDING_2D_MULTISAMPLE_ARRAY};

/// Capabilities every pass wants off, whatever the host left: each would change what a pass
/// writes (or keep it from writing at all) when on.
inline constexpr std::array<GLenum, 21> kPassOffCapabilities{
    GL_DEPTH_CLAMP,                    // casters beyond a layer's far plane would be drawn, clamped
    GL_RASTERIZER_DISCARD,             // nothing would be drawn or cleared
    GL_STENCIL_TEST,                   // a host's depth-stencil target given to the mask
    GL_COLOR_LOGIC_OP,                 // fixed-point mask targets would be combined, not written
    GL_FRAMEBUFFER_SRGB,               // an sRGB mask target would get encoded visibility
    GL_PRIMITIVE_RESTART,              // a caster's index could end its strip
    GL_PRIMITIVE_RESTART_FIXED_INDEX,  // 0xFF of a caster's 8-bit indices would
    GL_SAMPLE_ALPHA_TO_COVERAGE,       // the coverage of a multisample mask target
    GL_SAMPLE_ALPHA_TO_ONE,
    GL_SAMPLE_COVERAGE,
    GL_SAMPLE_MASK,
    GL_SAMPLE_SHADING,
    GL_POLYGON_SMOOTH,  // edge coverage into alpha
    GL_CLIP_DISTANCE0,  // clip distances no engine shader writes: undefined clipping
    GL_CLIP_DISTANCE1,
    GL_CLIP_DISTANCE2,
    GL_CLIP_DISTANCE3,
    GL_CLIP_DISTANCE4,
    GL_CLIP_DISTANCE5,
    GL_CLIP_DISTANCE6,
    GL_CLIP_DISTANCE7};

/// The pixel-unpack parameters, in the order `GlState::unpack` and `UnpackDefaults` keep them.
inline constexpr std::array<GLenum, 8> kUnpackParameters{
    GL_UNPACK_ALIGNMENT, GL_UNPACK_ROW_LENGTH,  GL_UNPACK_IMAGE_HEIGHT, GL_UNPACK_SKIP_PIXELS,
    GL_UNPACK_SKIP_ROWS, GL_UNPACK_SKIP_IMAGES, GL_UNPACK_SWAP_BYTES,   GL_UNPACK_LSB_FIRST};

/// The pieces of GL state the shadow system and the renderer change (see the header comment).
/// Texture units and uniform-buffer binding points are captured only for the ones named.
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
    std::array<GLdouble, 2> depthRange{0.0, 1.0};  ///< near, far
    GLint clipOrigin = GL_LOWER_LEFT;
    GLint clipDepthMode = GL_NEGATIVE_ONE_TO_ONE;
    std::array<GLint, 2> polygonMode{GL_FILL, GL_FILL};  ///< front, back (core: always equal)
    GLboolean cullFace = GL_FALSE;
    GLint cullFaceMode = GL_BACK;
    GLint frontFace = GL_CCW;
    GLboolean polygonOffsetFill = GL_FALSE;
    std::array<GLboolean, 8> blend{};                              ///< per draw buffer
    std::array<GLint, 4> blendFunc{};                              ///< src rgb, dst rgb, src alpha, dst alpha
    std::array<GLint, 2> blendEquation{GL_FUNC_ADD, GL_FUNC_ADD};  ///< rgb, alpha
    std::array<GLboolean, 4> colorMask{};
    std::array<GLboolean, kPassOffCapabilities.size()> offCapabilities{};  ///< in that order
    GLint packAlignment = 4;
    GLint packRowLength = 0;
    GLint packImageHeight = 0;
    GLint packSkipPixels = 0;
    GLint packSkipRows = 0;
    GLint packSkipImages = 0;
    GLboolean packSwapBytes = GL_FALSE;
    GLboolean packLsbFirst = GL_FALSE;
    GLint clampReadColor = GL_FIXED_ONLY;
    GLint pixelPackBuffer = 0;
    /// Pixel unpack, in `kUnpackParameters` order, and the unpack buffer (uploads set their own
    /// for their scope, `UnpackDefaults`).
    std::array<GLint, 8> unpack{4, 0, 0, 0, 0, 0, GL_FALSE, GL_FALSE};
    GLint pixelUnpackBuffer = 0;
    /// Which vertex of a triangle gives its flat outputs (the moment passes' flat varyings).
    GLint provokingVertex = GL_LAST_VERTEX_CONVENTION;
    GLint activeTexture = GL_TEXTURE0;
    GLint uniformBuffer = 0;  ///< the generic GL_UNIFORM_BUFFER binding
    struct Unit {
        GLint unit = 0;
        std::array<GLint, kTextureTargets.size()> textures{};  ///< per kTextureTargets entry
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
    /// The shader-storage bindings the mesh programs read (SG_BINDING_JOINTS, the joint matrices;
    /// SG_BINDING_MORPH_DELTAS, morph displacements; SG_BINDING_EDGE_COUNTS, the lit passes'
    /// edge counts), always captured, and the generic GL_SHADER_STORAGE_BUFFER binding.
    std::array<UniformBinding, 3> meshStorage{};
    GLint storageBuffer = 0;
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
/// Puts `state` back. An object the engine deleted after deletion mark `mark` (`deletionCount`),
/// or that is no longer an object of its kind, is left unbound rather than bound back (binding
/// a deleted name is GL_INVALID_OPERATION; GL itself unbinds what is deleted).
void restoreGlState(const GlState& state, std::uint64_t mark = UINT64_MAX);

/// The raster state every pass of the engine assumes, whatever the host left: scissor test off,
/// colour writes on, counter-clockwise front faces, filled polygons, no polygon offset, no
/// blending (additive equation for the passes that enable it), GL's clip control and depth
/// range, the last vertex provoking, and every capability of `kPassOffCapabilities` off. Each pass sets the rest
/// (framebuffer, viewport, depth, culling) itself. Every piece is in `GlState`.
void setPassDefaults();

/// Pixel-pack state for reading back into client memory, whatever the host left: no pack buffer,
/// rows tightly packed from the first pixel (alignment 1, no row length, image height or skips,
/// no byte swapping), float colours read unclamped. Every piece is in `GlState`.
void setReadbackDefaults();

/// For its scope, pixel-unpack state for uploading from tightly packed client memory, whatever
/// the host left (a row length, an alignment, an unpack buffer bound), and the host's put back
/// after: every upload of client memory into a texture stands in one.
class UnpackDefaults {
public:
    UnpackDefaults();
    ~UnpackDefaults();
    UnpackDefaults(const UnpackDefaults&) = delete;
    UnpackDefaults& operator=(const UnpackDefaults&) = delete;

private:
    std::array<GLint, 8> saved_{};
    GLint buffer_ = 0;
};

/// Captures on construction, restores on destruction (also when the scope is left by a throw).
class GlStateGuard {
public:
    GlStateGuard(std::span<const GLint> units, std::span<const GLint> uniformBindings,
                 std::span<const GLint> imageUnits = {})
        : saved_(captureGlState(units, uniformBindings, imageUnits)), mark_(deletionCount()) {}
    ~GlStateGuard() { restoreGlState(saved_, mark_); }
    GlStateGuard(const GlStateGuard&) = delete;
    GlStateGuard& operator=(const GlStateGuard&) = delete;

private:
    GlState saved_;
    std::uint64_t mark_ = 0;
};

}  // namespace shadow::gpu
