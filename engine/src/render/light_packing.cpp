#include "render/light_packing.h"

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>

namespace shadow::render {
namespace {

int lightTypeId(LightType t) {
    switch (t) {
        case LightType::Directional: return SG_LIGHT_DIRECTIONAL;
        case LightType::Spot: return SG_LIGHT_SPOT;
        case LightType::Point: return SG_LIGHT_POINT;
    }
    return SG_LIGHT_POINT;
}

// ShadowTechnique and SG_TECH_* list the techniques in the same order (shared_constants.h).
static_assert(static_cast<int>(ShadowTechnique::PcssTextbook) == SG_TECH_PCSS_TEXTBOOK);
int techniqueId(ShadowTechnique t) { return static_cast<int>(t); }

/// Adds the shadow of `plan` to `g`, its layers at `layers[firstLayer...]`.
void packShadow(const ShadowLightPlan& plan, const glm::dvec3& wsCamera, int firstLayer, gpu::GpuLight& g,
                gpu::GpuShadowLayer* layers) {
    const Shadow& s = plan.settings;
    g.technique = techniqueId(plan.technique());
    g.layerCount = static_cast<int>(plan.layers.size());
    g.constantBias = s.constantBias;
    g.slopeBias = s.slopeBias;
    g.normalOffset = s.normalOffset;
    g.pcfRadius = s.pcfRadius;
    g.pcfSamples = s.pcfSamples;
    g.blockerSamples = s.blockerSamples;
    g.maxFilterTexels = s.maxFilterTexels;
    g.mapSize = static_cast<float>(plan.mapSize);
    g.firstLayer = firstLayer;
    g.cascadeBlend = s.cascadeBlend;
    g.kernel = static_cast<int>(s.kernel);
    for (std::size_t k = 0; k < plan.layers.size(); ++k) layers[k] = packLayer(plan.layers[k], wsCamera);
}

}  // namespace

gpu::GpuLight packLight(const ShadowLightPlan& plan, const glm::dvec3& wsCamera) {
    const Light& light = plan.light;
    gpu::GpuLight g{};
    g.csPosition = glm::vec3(plan.wsPosition - wsCamera);
    g.wsDirection = glm::vec3(plan.wsDirection);
    g.type = lightTypeId(light.type);
    g.range = light.range;
    g.radiance = light.color * light.intensity;
    g.emitterSize = light.type == LightType::Directional ? light.angularRadius : light.radius;
    g.cosOuter = std::cos(light.outerConeAngle);
    g.cosInner = std::cos(light.innerConeAngle);
    g.technique = SG_TECH_NONE;
    return g;
}

gpu::GpuShadowLayer packLayer(const ShadowLayerPlan& layer, const glm::dvec3& wsCamera) {
    gpu::GpuShadowLayer l{};
    // Composed in double, so the float matrix is exact enough far from the origin.
    l.lightFromCs = glm::mat4(layer.lightFromWorld * glm::translate(glm::dmat4(1.0), wsCamera));
    l.clipFromLight = glm::mat4(layer.clipFromLight);
    l.depthScale = layer.depthScale;
    l.depthNear = layer.depthNear;
    l.splitFar = layer.splitFar;
    l.orthographic = layer.orthographic ? 1 : 0;
    return l;
}

void packLights(const ShadowFrame& frame, const glm::dvec3& wsCamera, std::vector<PassLights>& passes) {
    std::size_t used = 0;
    auto openPass = [&]() -> PassLights& {
        if (used == passes.size()) passes.emplace_back();
        PassLights& p = passes[used++];
        p.lights.fill(gpu::GpuLight{});
        p.sceneLight.fill(-1);
        p.variant.lights = 0;
        p.variant.type.fill(0);
        p.variant.technique.fill(0);
        p.variant.kernel.fill(0);
        return p;
    };
    PassLights* pass = &openPass();
    for (const ShadowLightPlan& plan : frame.lights) {
        if (!plan.shaded || !plan.affectsView) continue;  // contributes nothing; visibility 1
        if (pass->variant.lights == SG_MAX_LIGHTS_PER_PASS) pass = &openPass();
        const int slot = pass->variant.lights++;
        gpu::GpuLight& g = pass->lights[static_cast<std::size_t>(slot)];
        g = packLight(plan, wsCamera);
        const int firstLayer = slot * SG_MAX_LAYERS_PER_LIGHT;
        if (plan.hasMap()) packShadow(plan, wsCamera, firstLayer, g, &pass->layers[static_cast<std::size_t>(firstLayer)]);
        pass->sceneLight[static_cast<std::size_t>(slot)] = plan.sceneIndex;
        pass->variant.type[static_cast<std::size_t>(slot)] = static_cast<std::uint8_t>(g.type);
        pass->variant.technique[static_cast<std::size_t>(slot)] = static_cast<std::uint8_t>(g.technique);
        pass->variant.kernel[static_cast<std::size_t>(slot)] = static_cast<std::uint8_t>(g.kernel);
    }
    passes.resize(used);
}

}  // namespace shadow::render
