#include "core/light_records.h"

#include <shadow/shadow_shaders.h>

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace shadow::gpu {
namespace {

int lightTypeId(LightType t) {
    switch (t) {
        case LightType::Directional: return SG_LIGHT_DIRECTIONAL;
        case LightType::Spot: return SG_LIGHT_SPOT;
        case LightType::Point: return SG_LIGHT_POINT;
    }
    return SG_LIGHT_POINT;
}

/// Adds the shadow of `plan` to `g`, its layers at `slotLayers`, layer 0 at `firstLayer`.
void packShadow(const ShadowLightPlan& plan, const glm::dvec3& wsCamera, int firstLayer, GpuLight& g,
                GpuShadowLayer* slotLayers) {
    const Shadow& s = plan.settings;
    g.technique = static_cast<int>(plan.technique());
    g.layerCount = static_cast<int>(plan.layers.size());
    // Automatic lengths in texel footprints at the receiver: the shader adds the bias's parts and
    // takes the larger of the radius's (sg_pcfRadius).
    g.constantBias = isAutomatic(s.constantBias) ? 0.0f : s.constantBias;
    g.constantBiasTexels = isAutomatic(s.constantBias) ? kAutoConstantBiasTexels : 0.0f;
    g.slopeBias = s.slopeBias;
    g.normalOffset = s.normalOffset;
    g.pcfRadius = static_cast<float>(plan.pcfRadiusMetres);
    g.pcfRadiusTexels = isAutomatic(s.pcfRadius) ? kAutoPcfRadiusTexels : 0.0f;
    g.pcfSamples = s.pcfSamples;
    g.blockerSamples = s.blockerSamples;
    g.maxFilterTexels = plan.maxFilterTexels;
    g.mapSize = static_cast<float>(plan.mapSize);
    g.firstLayer = firstLayer;
    g.cascadeBlend = s.cascadeBlend;
    g.kernel = static_cast<int>(s.kernel);
    g.lightBleedReduction = s.lightBleedReduction;
    g.sdfFirst = plan.fieldFirst;
    g.sdfClusterFirst = plan.fieldClusterFirst;
    g.regionTest = plan.regionTest ? 1 : 0;
    g.sdfCount = static_cast<int>(plan.fieldCasters.size());
    g.sdfMapCasters = std::any_of(plan.layers.begin(), plan.layers.end(),
                                  [](const ShadowLayerPlan& layer) { return !layer.casters.empty(); })
                          ? 1
                          : 0;
    g.sdfSteps = s.sdfSteps;
    g.sdfStartOffset = s.sdfStartOffset;
    g.sdfMinStep = s.sdfMinStep;
    for (std::size_t k = 0; k < plan.layers.size(); ++k) slotLayers[k] = packLayer(plan.layers[k], wsCamera);
}

}  // namespace

GpuLight packSlot(const ShadowLightPlan& plan, const glm::dvec3& wsCamera, int slot, GpuShadowLayer* slotLayers) {
    const Light& light = plan.light;
    GpuLight g{};
    g.csPosition = glm::vec3(plan.wsPosition - wsCamera);
    g.wsDirection = glm::vec3(plan.wsDirection);
    g.type = lightTypeId(light.type);
    g.range = light.range;
    g.radiance = light.color * light.intensity;
    g.emitterSize = emitterSize(light);
    g.cosOuter = std::cos(light.outerConeAngle);
    g.cosInner = std::cos(light.innerConeAngle);
    g.technique = SG_TECH_NONE;
    if (plan.hasMap()) packShadow(plan, wsCamera, slot * SG_MAX_LAYERS_PER_LIGHT, g, slotLayers);
    return g;
}

GpuShadowLayer packLayer(const ShadowLayerPlan& layer, const glm::dvec3& wsCamera) {
    GpuShadowLayer l{};
    // Composed in double, so the float matrix is exact enough far from the origin.
    l.lightFromCs = glm::mat4(layer.lightFromWorld * glm::translate(glm::dmat4(1.0), wsCamera));
    l.clipFromLight = glm::mat4(layer.clipFromLight);
    l.depthScale = layer.depthScale;
    l.depthNear = layer.depthNear;
    l.blockerNear = layer.blockerNear;
    l.splitFar = layer.splitFar;
    l.orthographic = layer.orthographic ? 1 : 0;
    l.momentScale = layer.momentScale;
    l.chainFirstLevel = layer.chainFirstLevel;
    l.chainLastLevel = layer.chainLastLevel;
    return l;
}

std::vector<glm::vec2> poissonDisk(int count) {
    std::vector<glm::vec2> points;
    std::uint32_t state = 0x9e3779b9u;
    auto next = [&state] {  // xorshift32
        state ^= state << 13;
        state ^= state >> 17;
        state ^= state << 5;
        return static_cast<float>(state) * (1.0f / 4294967296.0f);
    };
    while (static_cast<int>(points.size()) < count) {
        glm::vec2 best(0.0f);
        float bestDistance = -1.0f;
        for (int c = 0; c < 32 * static_cast<int>(points.size() + 1); ++c) {
            const float r = std::sqrt(next());
            const float a = 6.28318531f * next();
            const glm::vec2 candidate(r * std::cos(a), r * std::sin(a));
            float nearest = 4.0f;
            for (const glm::vec2& p : points) nearest = std::min(nearest, glm::distance(p, candidate));
            if (nearest > bestDistance) {
                bestDistance = nearest;
                best = candidate;
            }
        }
        points.push_back(best);
    }
    return points;
}

}  // namespace shadow::gpu
