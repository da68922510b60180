// The screen-space visibility stage of the renderer (RenderOptions::screenVisibility): the
// scene drawn once into surface targets (depth along the view, normals, material), then per
// lit pass each group of four lights' visibility computed over the screen at the resolution its
// penumbrae need and brought back to full resolution without crossing geometric edges
// (shaders/screen_visibility.frag.glsl), then the pass's lights shaded by one full-screen
// triangle that reads both (lit.frag.glsl with SG_DEFERRED).
//
// Bringing a reduced stage back to full resolution: the lit pass does it itself for the groups
// it can (`litResolveDivisors`): it blends the stage's samples (sg_resolveStage) and marks the
// lights whose pixels the blend cannot serve; a mark pass turns the marks into depth, and the
// pass's correction (the lit program with SG_LIT_CORRECTION) adds those lights, their technique
// run at full resolution, at the marked pixels alone. The other groups (contact shadows, a
// second divisor) keep passes of their own: the resolve writes the full-resolution visibility
// and marks, the refine recomputes the marked pixels, the lit pass reads the result.
//
// Why: a soft shadow's penumbra is low-frequency, yet the forward lit pass pays its filter at
// every fragment of the scene, at a CPU rasteriser's scene rate (small triangles shade partly
// covered blocks: twice a full-screen pass's cost per pixel, BENCHMARKS.md fragment costs).
#pragma once

#include "core/stage_resolution.h"
#include "gl/objects.h"
#include "gl/pass_timer.h"
#include "render/light_packing.h"

#include <shadow/renderer.h>
#include <shadow/stats.h>

#include <glm/glm.hpp>

#include <array>
#include <map>
#include <tuple>

namespace shadow::render {

/// The divisor of the screen resolution at which a group of lights' visibility is computed:
/// `setting` when it forces one (Full, Half, Quarter); for Auto 1 when every shadowed light of
/// the group has hard-edged shadows (technique hard, or none) or the image has fewer than
/// `kMinStageHeight` rows (`height`), else `stageDivisor`'s 2 or 4. Pure CPU.
[[nodiscard]] int visibilityDivisor(ScreenVisibility setting, const LitVariant& variant, int firstSlot, int slots,
                                    int height);

/// Whether a frame of `passes` (lights of `frame`) runs the stage under `setting`: never when
/// Off, always when it forces a resolution. For Auto, where the stage measured faster than the
/// forward passes on llvmpipe (BENCHMARKS.md, screen-space visibility): a light with technique
/// pcss or sdf (their filters are the dearest: at 1280x720 sdf 0.25 of forward's frame on
/// the bunny spots, PCSS 0.68-0.70), or two or more lights that filter (any technique but hard:
/// the sample scenes 0.49-0.80); and always when a light asks for contact shadows, which only
/// the stage draws.
/// One PCF, VSM, VSSM or MSM light alone stays forward under `kMinQuarterStageHeight` rows: there
/// its lookups cost about what the stage's surface and full-screen passes do (the stage forced at
/// half resolution, bunny spots at 1280x720: 0.86-1.05 of forward's frame); from those rows the
/// stage runs it at quarter resolution, measured 0.88-0.89 of forward (PCF), 0.90-0.93 (VSSM)
/// and 0.73-0.75 (MSM-soft), at an error against the truth equal or lower (README,
/// "Screen-space visibility"). Hard shadows stay forward, and so
/// does an image under `kMinStageHeight` rows, contact shadows aside.
[[nodiscard]] bool screenStagePays(ScreenVisibility setting, const ShadowFrame& frame,
                                   const std::vector<PassLights>& passes, int height);

/// Per group of four slots of `pass` (k: slots 4k to 4k + 3), the divisor at which the deferred
/// lit pass resolves the stage itself (LitVariant::resolve): the group's `visibilityDivisor` when
/// above 1 and no light of the group has contact shadows (whose march the stage's refine pass
/// draws), 0 where the stage's own passes bring the group to full resolution (its stage at full
/// resolution, a contact march, a group without a shadowed light). The lit pass reads one reduced
/// stage: a second group at another divisor than the first is left to the stage's passes.
/// Why: the resolve as a pass of its own cost 13.9 ms of the bunny spot's 64 ms PCF frame at
/// 1280x720, a full-screen pass's floor (5.7 ms) of it spent writing what the lit pass then read.
[[nodiscard]] std::array<std::uint8_t, 2> litResolveDivisors(ScreenVisibility setting, const ShadowFrame& frame,
                                                             const PassLights& pass, int height);

/// The contact march's length of `light` as the stage's shader takes it: metres (> 0), -1 for
/// the automatic length, 0 without contact shadows or technique.
[[nodiscard]] float contactLengthUniform(const ShadowLightPlan& light);

/// The camera as the stage's passes see it (camera-relative, world axes).
struct ScreenRays {
    glm::vec3 forward{0.0f, 0.0f, -1.0f};  ///< unit view direction
    float pixelAngle = 0.0f;               ///< a pixel's height per metre of depth
    /// The ray through pixel centre p at unit depth: ray00 + (p.x + 0.5) dx + (p.y + 0.5) dy.
    glm::vec3 ray00{0.0f}, dx{0.0f}, dy{0.0f};
    glm::mat4 clipFromCs{1.0f};  ///< camera-relative world -> clip
};

/// The stage's targets and programs. Requires a current context with `loadGl` done.
class ScreenStage {
public:
    ScreenStage();
    /// GPU memory (bytes) of the stage's targets for `width` x `height`, with the material
    /// targets (`ensure`) when `materialTargets`.
    [[nodiscard]] static std::int64_t bytesFor(int width, int height, bool materialTargets);
    /// Makes the targets fit `width` x `height`, the surface framebuffer sharing `depthBuffer`;
    /// with `materialTargets` (a frame with normal maps or emission) also the lighting normal's
    /// and the emission's, made on first use.
    void ensure(int width, int height, GLuint depthBuffer, bool materialTargets);
    /// Binds the surface framebuffer and clears it (coverage 0, depth far); it draws into the
    /// material targets too when `materialTargets`.
    void beginSurfaces(bool materialTargets);
    /// Runs the visibility of pass `pass` (whose records and shadow resources are bound) into the
    /// full-resolution visibility array, group by group, within `bounds` (full-resolution pixels:
    /// the pass's lights' reach, or the screen where the lit pass writes every light's visibility
    /// AOV); leaves the stage's framebuffer bound. A group the lit pass resolves itself
    /// (LitVariant::resolve) gets its reduced-resolution stage alone.
    /// Contact shadows for the lights of `frame` that ask for them (`Shadow::contactShadows`).
    /// With `timer`, each kind of pass is timed on its own: Main/ScreenVisibility/stage, /resolve
    /// (the upsample) and /refine.
    void computeVisibility(const ShadowFrame& frame, const PassLights& pass, const PixelRect& bounds,
                           ScreenVisibility setting, const ScreenRays& rays, FrameStats& stats, gpu::PassTimer* timer);
    /// Binds the surface targets (with the material targets when `materialTargets`), the
    /// full-resolution visibility and, for a pass that resolves the stage itself (`pass`'s
    /// LitVariant::resolve), the stage its `computeVisibility` drew, for the deferred lit pass.
    void bindForLighting(bool materialTargets, const LitVariant& pass) const;
    /// The marks target a deferred lit pass that resolves the stage writes (R8UI, SG_OUT_MARKS).
    [[nodiscard]] GLuint marks() const { return marks_.get(); }
    /// Prepares a correction of a deferred lit pass that resolved the stage: the pixels where it
    /// marked one of the slots of `slotBits` (within `bounds`) as depth 0 in `correctionDepth`,
    /// the rest 1, and the marks bound for the correction to read (SG_UNIT_LIT_STAGE). Leaves the
    /// stage's framebuffer bound.
    void markCorrection(const PixelRect& bounds, unsigned slotBits, FrameStats& stats);
    /// The depth buffer `markCorrection` fills, against which the correction is tested.
    [[nodiscard]] GLuint correctionDepth() const { return refine_.get(); }
    /// An empty vertex array for full-screen triangles.
    [[nodiscard]] GLuint emptyVertexArray() const { return empty_.get(); }

private:
    struct Program {
        gpu::Program program;
        GLint cameraForward = -1, pixelAngle = -1, stageLayer = -1, ray00 = -1, rayDx = -1, rayDy = -1;
        GLint contactLength = -1, clipFromCs = -1;
    };
    /// A group's draws: the stage (at its divisor, or at full resolution), the resolve of a
    /// reduced stage, and the refine after it (the stage at full resolution for the lights the
    /// resolve left).
    enum class Pass { Stage, Resolve, Refine };
    /// Group slots' configuration, first slot, divisor, pass, contact shadows.
    using Key = std::tuple<LitVariant, int, int, Pass, bool>;
    Program& program(const LitVariant& group, int firstSlot, int divisor, Pass pass, bool contact, FrameStats& stats);
    /// A group of up to four slots of a pass, as its draws need it.
    struct Group {
        LitVariant variant;  ///< the group's slots alone
        int first = 0;       ///< its first slot in the pass
        int layer = 0;       ///< its layer of the visibility arrays
        int divisor = 1;
        glm::vec4 contactLength{0.0f};  ///< per channel, `contactLengthUniform`
        bool contact = false;
        PixelRect bounds;  ///< where its visibility is wanted, in full-resolution pixels
    };
    /// The group's visibility at full resolution: the stage, or at a reduced resolution the
    /// stage, the resolve and the refine.
    void visibilityOfGroup(const Group& g, const ScreenRays& rays, FrameStats& stats, gpu::PassTimer* timer);
    /// The stage at the group's reduced resolution, depth-tested against its coverage.
    void reducedStage(const Group& g, const ScreenRays& rays, FrameStats& stats);
    /// One full-screen draw of `p` for group `g` at 1/`divisor` of the resolution.
    void draw(Program& p, const Group& g, int divisor, const ScreenRays& rays) const;
    void ensureStageTarget(int divisor);
    /// The full-size targets and the surface framebuffer, anew for `width` x `height`.
    void makeTargets(int width, int height);
    /// The coverage of the stage at `divisor`, drawn once a frame, attached as the depth buffer.
    void attachCoverage(int divisor, FrameStats& stats);

    int width_ = 0, height_ = 0;
    GLuint depthBuffer_ = 0;  ///< the renderer's, which the surface pass fills
    gpu::Framebuffer surfaces_, visibility_;
    gpu::Texture surface_, material_;         ///< RGBA32UI, packed as shaders/screen_gbuffer.glsl says
    gpu::Texture extra_;                      ///< RGBA32UI: emission and lighting normal (material targets)
    gpu::Texture full_;                       ///< RGBA8 array: slots 0-3, 4-7 of the pass
    gpu::Texture refine_;                     ///< depth 0 marks the pixels the refine pass recomputes
    gpu::Texture prior_;                      ///< RGBA16F: the resolve's visibility, -1 where the refine recomputes
    std::array<gpu::Texture, 3> stage_;       ///< reduced-resolution arrays by divisor 2, 4 (index 1, 2)
    std::array<gpu::Texture, 3> stageDepth_;  ///< their samples' depths and codes (R32UI, screen_resolve.glsl)
    std::array<gpu::Texture, 3> coverage_;    ///< their depth buffers: 0 where a sample receives
    std::array<gpu::Program, 3> coveragePrograms_;
    unsigned coverageDrawn_ = 0;  ///< bit per divisor index: its coverage is this frame's
    gpu::Texture marks_;          ///< R8UI: the deferred lit pass's marks (SG_OUT_MARKS)
    gpu::Program marksProgram_;   ///< their depth for the correction (screen_coverage.frag.glsl)
    GLint marksBits_ = -1;        ///< its uMarkBits
    gpu::VertexArray empty_;
    std::map<Key, Program> programs_;
};

}  // namespace shadow::render
