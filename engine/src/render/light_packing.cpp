#include "render/light_packing.h"

#include "core/light_records.h"
#include "core/stage_resolution.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <span>

namespace shadow::render {
namespace {

/// Pass `used` (growing `passes` when needed), emptied; the first pass covers the whole screen.
PassLights& openPass(std::vector<PassLights>& passes, std::size_t& used, const PixelRect& whole) {
    if (used == passes.size()) passes.emplace_back();
    PassLights& p = passes[used++];
    p.lights.fill(gpu::GpuLight{});
    p.sceneLight.fill(-1);
    p.variant.lights = 0;
    p.variant.type.fill(0);
    p.variant.technique.fill(0);
    p.variant.kernel.fill(0);
    p.bounds = used == 1 ? whole : PixelRect{};
    p.wsReach = DAabb{};
    p.unbounded = used == 1;
    return p;
}

/// Puts `plan` (its packing `entry`) in the next slot of `pass`: records, variant key, bounds.
void addToPass(PassLights& pass, const ShadowLightPlan& plan, const PackingEntry& entry, const glm::dvec3& wsCamera) {
    const auto slot = static_cast<std::size_t>(pass.variant.lights++);
    gpu::GpuLight& g = pass.lights[slot];
    g = gpu::packSlot(plan, wsCamera, static_cast<int>(slot), &pass.layers[slot * SG_MAX_LAYERS_PER_LIGHT]);
    pass.sceneLight[slot] = plan.sceneIndex;
    pass.variant.type[slot] = static_cast<std::uint8_t>(g.type);
    pass.variant.technique[slot] = static_cast<std::uint8_t>(g.technique);
    pass.variant.kernel[slot] = static_cast<std::uint8_t>(g.kernel);
    pass.bounds = unite(pass.bounds, entry.bounds);
    if (entry.wide || plan.light.type == LightType::Directional || !(plan.light.range > 0.0f)) {
        pass.unbounded = true;
    } else {
        pass.wsReach.extend(plan.wsPosition - glm::dvec3(plan.light.range));
        pass.wsReach.extend(plan.wsPosition + glm::dvec3(plan.light.range));
    }
}

}  // namespace

LitVariant slotsVariant(const LitVariant& pass, int first, int count) {
    LitVariant g;
    g.lights = count;
    for (int i = 0; i < count; ++i) {
        const auto d = static_cast<std::size_t>(i);
        const auto s = static_cast<std::size_t>(first) + static_cast<std::size_t>(i);
        g.type[d] = pass.type[s];
        g.technique[d] = pass.technique[s];
        g.kernel[d] = pass.kernel[s];
    }
    return g;
}

bool refinesPerLight(const LitVariant& pass, int first, int count) {
    return shadow::refinesPerLight(
        std::span(pass.technique).subspan(static_cast<std::size_t>(first), static_cast<std::size_t>(count)));
}

void packLights(const ShadowFrame& frame, const glm::dvec3& wsCamera, const ScreenView& view,
                std::vector<PassLights>& passes, std::vector<PackingEntry>& order) {
    const PixelRect whole{0, 0, view.width, view.height};
    order.clear();
    for (const ShadowLightPlan& plan : frame.lights) {
        if (!plan.shaded || !plan.affectsView) continue;  // contributes nothing; visibility 1
        const PixelRect b = screenBounds(plan, view);
        if (b.empty()) continue;  // its sphere is off screen
        // Lights that reach a quarter of the screen or more join the first, whole-screen pass
        // while it has room: another pass over the scene's triangles would cost more than the
        // pixels they leave out.
        const bool wide = 4 * b.area() >= whole.area();
        const std::uint32_t config = static_cast<std::uint32_t>(plan.light.type) << 16 |
                                     static_cast<std::uint32_t>(plan.technique()) << 8 |
                                     static_cast<std::uint32_t>(plan.settings.kernel);
        order.push_back({wide, plan.sceneIndex, b, config});
    }
    // When every light fits in one pass, one pass it is (another pass over the triangles costs
    // more than the pixels it would spare); otherwise local lights start passes of their own.
    const bool onePass = order.size() <= SG_MAX_LIGHTS_PER_PASS;
    // Wide lights first, in scene order (over several passes, those alike together); the local
    // ones after them. Scene order is spelled out rather than left to std::stable_sort, which
    // allocates a buffer every call.
    std::sort(order.begin(), order.end(), [onePass](const PackingEntry& a, const PackingEntry& b) {
        if (a.wide != b.wide) return a.wide;
        if (!onePass && a.wide && a.config != b.config) return a.config < b.config;
        return a.sceneLight < b.sceneLight;
    });

    std::size_t used = 0;
    PassLights* pass = &openPass(passes, used, whole);
    for (const PackingEntry& entry : order) {
        const bool local = !onePass && !entry.wide;
        if (pass->variant.lights == SG_MAX_LIGHTS_PER_PASS || (local && (used == 1 || pass->variant.lights > 0))) {
            pass = &openPass(passes, used, whole);
        }
        addToPass(*pass, frame.lights[static_cast<std::size_t>(entry.sceneLight)], entry, wsCamera);
    }
    passes.resize(used);
}

}  // namespace shadow::render
