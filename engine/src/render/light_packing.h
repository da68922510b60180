// Light packing: the shadow frame's lights as the main pass's uniform-block records, grouped
// into passes of up to SG_MAX_LIGHTS_PER_PASS lights. Pure CPU (tested without GL).
#pragma once

#include <shadow/gpu_records.h>
#include <shadow/shadow_planner.h>

#include "core/screen_bounds.h"

#include <array>
#include <compare>
#include <cstdint>
#include <vector>

namespace shadow::render {

/// The light configuration a lit program is specialised for: per slot the light type and the
/// technique its pixels use and its filter kernel (compile-time constants in the shader), plus what it writes.
struct LitVariant {
    int lights = 0;                                                ///< slots in use
    std::array<std::uint8_t, SG_MAX_LIGHTS_PER_PASS> type{};       ///< SG_LIGHT_*
    std::array<std::uint8_t, SG_MAX_LIGHTS_PER_PASS> technique{};  ///< SG_TECH_*
    std::array<std::uint8_t, SG_MAX_LIGHTS_PER_PASS> kernel{};     ///< SG_KERNEL_*
    bool aovs = false;
    /// The screen-space visibility stage's lit pass: surfaces and visibility read per pixel.
    bool deferred = false;
    /// Forward: the maps variant of the material (SG_MATERIAL_MAPS); deferred: the surfaces hold
    /// a lighting normal and emission (SG_GBUFFER_MATERIAL).
    bool materialMaps = false;
    int debugView = SG_DEBUG_NONE;  ///< SG_DEBUG_*
    int debugSlot = -1;             ///< slot the debug view shows, -1 none
    /// Forward: the deformation of the meshes it draws (gpu::MeshDeformBits); 0 deferred.
    unsigned deform = 0;
    /// Forward, a frame that counts a slot's auto light's edges (`ShadowLightPlan::countEdges`):
    /// the counting program (SG_COUNT_EDGES; the hard lookup compiled in for the count).
    bool countEdges = false;
    /// Deferred, per group of four slots (k: slots 4k to 4k + 3): the divisor of the stage the
    /// lit pass resolves itself (SG_LAYER<k>_RESOLVE, `litResolveDivisors`), 0 where it reads the
    /// visibility the stage's passes brought to full resolution.
    std::array<std::uint8_t, 2> resolve{};
    /// Deferred, resolving: the program of the pass's correction (SG_LIT_CORRECTION), which adds
    /// the lights the lit pass marked, at the marked pixels.
    bool correction = false;
    /// A correction's first slot in its pass (SG_SLOT_BASE): it compiles one group of four.
    std::uint8_t slotBase = 0;
    /// The first lit pass, which adds the hemisphere ambient and the emission (SG_LIT_AMBIENT);
    /// the passes after it and the corrections add their lights alone. Compiled in, not a
    /// uniform's loop: a loop of 0 or 1 trips on a uniform cost the bunny spot's lit pass at
    /// 1920x1080 3.5 ms on llvmpipe, more than the ambient's arithmetic.
    bool ambient = true;
    /// Forward: a material of the frame has a base-colour texture (SG_BASE_COLOR_TEXTURE); a
    /// frame without one fetches none (the fetch, selected away for an untextured material,
    /// cost the bunny spot's lit pass about 1 ms at 1280x720 on llvmpipe).
    bool textured = true;

    auto operator<=>(const LitVariant&) const = default;
};

/// A light on its way into a pass: wide (it reaches a quarter of the screen or more) or local,
/// its scene index and screen bounds.
struct PackingEntry {
    bool wide = false;
    int sceneLight = -1;
    PixelRect bounds;
    /// Type, technique and kernel of its slot, as one number: wide lights alike share passes.
    std::uint32_t config = 0;
};

/// One main pass: its lights' records, the scene light of each slot, and its variant.
struct PassLights {
    std::array<gpu::GpuLight, SG_MAX_LIGHTS_PER_PASS> lights{};
    /// Layer k of slot s at s * SG_MAX_LAYERS_PER_LIGHT + k.
    std::array<gpu::GpuShadowLayer, std::size_t{SG_MAX_LIGHTS_PER_PASS} * SG_MAX_LAYERS_PER_LIGHT> layers{};
    std::array<int, SG_MAX_LIGHTS_PER_PASS> sceneLight{};  ///< -1 for an unused slot
    LitVariant variant;
    /// The pixels its lights can reach (the union of their bounds); the first pass covers the
    /// whole screen (it resolves depth and adds the ambient term).
    PixelRect bounds;
    /// The world box its lights can reach (the union of their range spheres' boxes); empty for a
    /// pass with a light of unbounded reach, which draws every mesh.
    DAabb wsReach;
    bool unbounded = true;
};

/// Packs the lights of `frame` that can shade the view (`shaded` and `affectsView`) into
/// `passes`, positions relative to `wsCamera`. When they all fit (SG_MAX_LIGHTS_PER_PASS), one
/// whole-screen pass holds them, in scene order. Otherwise lights that reach a quarter of the
/// screen or more fill whole-screen passes of up to SG_MAX_LIGHTS_PER_PASS, lights of the same
/// type, technique and kernel together (in scene order among them), so that passes share
/// programs and a program compiles each configuration once; and every other light gets
/// a pass of its own, bounded on screen and in the world by its range: a pixel then pays for the
/// lights that can reach it, since a CPU rasteriser runs every light of a pass at every pixel of
/// it (both sides of an `if` run; BENCHMARKS.md, fragment costs). There is always at least one
/// pass (it resolves depth and writes the ambient term and the AOVs). Reuses the capacity of
/// `passes` and `order` (scratch): no allocation once they have grown.
void packLights(const ShadowFrame& frame, const glm::dvec3& wsCamera, const ScreenView& view,
                std::vector<PassLights>& passes, std::vector<PackingEntry>& order);

/// Slots `first` .. `first + count - 1` of a pass's variant as a variant of their own (their
/// type, technique and kernel; nothing else set).
[[nodiscard]] LitVariant slotsVariant(const LitVariant& pass, int first, int count);

/// `shadow::refinesPerLight` (core/stage_resolution.h) of slots `first` .. `first + count - 1`
/// of a pass's variant: whether that group's marked pixels are recomputed light by light.
[[nodiscard]] bool refinesPerLight(const LitVariant& pass, int first, int count);

}  // namespace shadow::render
