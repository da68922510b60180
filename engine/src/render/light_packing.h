// Light packing: the shadow frame's lights as the main pass's uniform-block records, grouped
// into passes of up to SG_MAX_LIGHTS_PER_PASS lights. Pure CPU (tested without GL).
#pragma once

#include <shadow/shadow_system.h>

#include "render/gpu_types.h"

#include <array>
#include <compare>
#include <cstdint>
#include <vector>

namespace shadow::render {

/// The light configuration a lit program is specialised for: per slot the light type and the
/// technique its pixels use and its filter kernel (compile-time constants in the shader), plus what it writes.
struct LitVariant {
    int lights = 0;  ///< slots in use
    std::array<std::uint8_t, SG_MAX_LIGHTS_PER_PASS> type{};       ///< SG_LIGHT_*
    std::array<std::uint8_t, SG_MAX_LIGHTS_PER_PASS> technique{};  ///< SG_TECH_*
    std::array<std::uint8_t, SG_MAX_LIGHTS_PER_PASS> kernel{};     ///< SG_KERNEL_*
    bool aovs = false;
    int debugView = SG_DEBUG_NONE;  ///< SG_DEBUG_*
    int debugSlot = -1;             ///< slot the debug view shows, -1 none

    auto operator<=>(const LitVariant&) const = default;
};

/// One main pass: its lights' records, the scene light of each slot, and its variant.
struct PassLights {
    std::array<gpu::GpuLight, SG_MAX_LIGHTS_PER_PASS> lights{};
    /// Layer k of slot s at s * SG_MAX_LAYERS_PER_LIGHT + k.
    std::array<gpu::GpuShadowLayer, SG_MAX_LIGHTS_PER_PASS * SG_MAX_LAYERS_PER_LIGHT> layers{};
    std::array<int, SG_MAX_LIGHTS_PER_PASS> sceneLight{};  ///< -1 for an unused slot
    LitVariant variant;
};

/// Packs the lights of `frame` that can shade the view (`shaded` and `affectsView`) into
/// `passes`, SG_MAX_LIGHTS_PER_PASS per pass in scene order, positions relative to
/// `wsCamera`. There is always at least one pass (it writes the ambient term and the AOVs).
/// Reuses the capacity of `passes`: no allocation once it has grown.
void packLights(const ShadowFrame& frame, const glm::dvec3& wsCamera, std::vector<PassLights>& passes);

/// `light` as the shader reads it, without its shadow (technique None).
gpu::GpuLight packLight(const ShadowLightPlan& light, const glm::dvec3& wsCamera);

/// The layer record of `layer`, its matrices made to take camera-relative positions.
gpu::GpuShadowLayer packLayer(const ShadowLayerPlan& layer, const glm::dvec3& wsCamera);

}  // namespace shadow::render
