// The screen-space shadow mask: a full-screen pass over a game's depth buffer that writes the
// visibility of up to SG_MAX_MASK_LIGHTS lights into the channels of the game's texture, for a
// game that multiplies it into its lighting without any shader of the module.
#pragma once

#include <shadow/gl_handles.h>
#include <shadow/result.h>
#include <shadow/scene.h>
#include <shadow/shadow_maps.h>
#include <shadow/shadow_planner.h>
#include <shadow/stats.h>

#include <glm/glm.hpp>

#include <memory>
#include <span>

namespace shadow {

/// Where the mask's visibility is computed (`ShadowMaskRequest::resolution`), as the renderer's
/// screen-space stage computes it (`ScreenVisibility`).
enum class MaskResolution {
    /// Every pixel runs its lights' techniques.
    Full,
    /// One sample per 2x2 (Half) or 4x4 (Quarter) block runs them; each pixel then blends the
    /// samples around it that lie on its own surface and face as it does (never across a
    /// geometric edge), and the pixels without one, whose samples disagree by more than 0.1 (a
    /// hard edge, a contact) or whose nearest sample found a shadow narrower than its block
    /// nearby, run at full resolution. Three passes instead of one, and two targets of the
    /// mask's own.
    Half,
    Quarter,
    /// Half or Quarter where a light of the mask filters its shadows (any technique but hard)
    /// and the image has 360 rows or more (Quarter from 720), Full otherwise: the renderer's
    /// rule (README, "Screen-space visibility").
    Auto,
};

/// What `ShadowMask::render` draws from and into. The receiver is rebuilt from depth (and the
/// normals when given), so the mask matches the module's forward visibility on surfaces and can
/// differ at silhouettes, where depth has no plane.
struct ShadowMaskRequest {
    /// GL_TEXTURE_2D with the game's window depth (a depth format, or R32F), `width` x `height`.
    GlTexture depthTexture;
    /// Optional GL_TEXTURE_2D of world-space shading normals in xyz (any length; turned to face
    /// the camera); none: the normal of the surface rebuilt from depth.
    GlTexture normalTexture;
    /// GL_TEXTURE_2D the mask is written to (colour-renderable: RGBA8, RGBA16F, RG16, R8, ...;
    /// channels beyond the format's are dropped, channels of no light are 1), `width` x `height`.
    GlTexture target;
    int width = 0;   ///< pixels, >= 1
    int height = 0;  ///< pixels, >= 1
    /// The camera the depth was drawn with; the lights' records are made relative to its position.
    CameraView camera;
    /// The projection the depth was drawn with (view -> clip). All zero (the default): the
    /// perspective of `camera` with GL's [-1, 1] depth, as the module's renderer draws.
    glm::dmat4 clipFromView{0.0};
    /// True when the game set glClipControl(..., GL_ZERO_TO_ONE): window depth is NDC z.
    bool zeroToOneDepth = false;
    /// Window depth of pixels without geometry: 1 with GL's default clear, 0 for reversed Z.
    float backgroundDepth = 1.0f;
    /// Evaluate each light only within its screen bounds (its range); the rest of the target is
    /// written 1 by a clear. Off: every pixel runs every light.
    bool scissorToLights = true;
    /// Where the visibility is computed. Full (the default): what the module's forward passes
    /// compute, pixel for pixel.
    MaskResolution resolution = MaskResolution::Full;
};

/// The mask pass: its programs (one per light configuration, compiled on first use), and the
/// light records it uploads into buffers of its own (a game's bound shader inputs stay as they
/// are). Requires a current OpenGL 4.5 context with `loadGl` done.
class ShadowMask {
public:
    /// Throws `GlError` when `loadGl` has not run.
    ShadowMask();
    /// For a game built without exceptions: the mask, or the error the constructor would throw.
    [[nodiscard]] static Result<std::unique_ptr<ShadowMask>> create() noexcept;
    ~ShadowMask();
    ShadowMask(const ShadowMask&) = delete;
    ShadowMask& operator=(const ShadowMask&) = delete;

    /// Writes the mask of scene lights `sceneLights` (up to SG_MAX_MASK_LIGHTS; light i in
    /// channel i) of `frame`, with the maps of `maps` rendered from it, into `request.target`.
    /// Each light's technique is the one the module's renderer uses, compiled only for the light
    /// configurations asked for. A guest like `ShadowMaps::render`: the GL state it changes is put
    /// back, a host error pending before the call is a `HostGlError` warning in `stats` (with
    /// those its constructor found). Throws `std::invalid_argument` naming the problem for too
    /// many lights, a light that is not a scene light, no texture or a size below 1; `GlError`
    /// when the target cannot be drawn to.
    void render(const ShadowFrame& frame, const ShadowMaps& maps, std::span<const int> sceneLights,
                const ShadowMaskRequest& request, FrameStats& stats);
    /// `render` for a game built without exceptions.
    [[nodiscard]] Status tryRender(const ShadowFrame& frame, const ShadowMaps& maps, std::span<const int> sceneLights,
                                   const ShadowMaskRequest& request, FrameStats& stats) noexcept;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace shadow
