// ShadowPlanner: the CPU "decide" phase of the shadow system (see shadow_system.h).
#include <shadow/shadow_system.h>

#include "shadow/frustum.h"
#include "shadow/light_projection.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace shadow {
namespace {

template <typename T>
void clampField(T& value, T lo, T hi, const std::string& who, const char* field,
                std::vector<std::string>& warnings) {
    T clamped = value;
    if constexpr (std::is_floating_point_v<T>) {
        if (!std::isfinite(value)) clamped = lo;
    }
    clamped = std::clamp(clamped, lo, hi);
    if (clamped != value) {
        std::ostringstream msg;
        msg << who << ": " << field << " " << value << " clamped to " << clamped;
        warnings.push_back(msg.str());
        value = clamped;
    }
}

const char* lightName(const World& world, Entity e) {
    const Name* n = world.tryGet<Name>(e);
    return n != nullptr ? n->value.c_str() : "light";
}

}  // namespace

void clampShadowSettings(Shadow& s, Light& light, const ShadowLimits& limits, const std::string& who,
                         std::vector<std::string>& warnings) {
    clampField(s.mapSize, 1, std::max(1, limits.maxTextureSize), who, "mapSize", warnings);
    clampField(s.constantBias, 0.0f, 10.0f, who, "constantBias", warnings);
    clampField(s.slopeBias, 0.0f, 16.0f, who, "slopeBias", warnings);
    clampField(s.normalOffset, 0.0f, 16.0f, who, "normalOffset", warnings);
    clampField(s.pcfRadius, 0.0f, 10.0f, who, "pcfRadius", warnings);
    clampField(s.pcfSamples, 1, 64, who, "pcfSamples", warnings);
    clampField(s.blockerSamples, 1, 64, who, "blockerSamples", warnings);
    clampField(s.maxFilterTexels, 1.0f, 256.0f, who, "maxFilterTexels", warnings);
    clampField(s.cascades, 1, 4, who, "cascades", warnings);
    clampField(s.cascadeSplitLambda, 0.0f, 1.0f, who, "cascadeSplitLambda", warnings);
    clampField(s.cascadeBlend, 0.0f, 0.5f, who, "cascadeBlend", warnings);
    clampField(s.shadowDistance, 0.0f, 1e7f, who, "shadowDistance", warnings);
    clampField(s.nearPlane, 0.0f, 1e7f, who, "nearPlane", warnings);
    clampField(light.radius, 0.0f, 1e3f, who, "radius", warnings);
    clampField(light.angularRadius, 0.0f, 0.2f, who, "angularRadius", warnings);
    clampField(light.outerConeAngle, 1e-4f, kMaxSpotHalfAngle, who, "outerConeAngle", warnings);
    clampField(light.innerConeAngle, 0.0f, light.outerConeAngle, who, "innerConeAngle", warnings);
    clampField(light.range, 0.0f, 1e7f, who, "range", warnings);
}

const ShadowFrame& ShadowPlanner::prepare(World& world, const CameraView& camera,
                                          const std::vector<Entity>& lights) {
    frame_.lights.clear();
    frame_.warnings.clear();
    const SceneGeometry geometry = gatherGeometry(world);
    const Frustum cameraFrustum = Frustum::fromMatrix(cameraClipFromWorld(camera));

    for (std::size_t i = 0; i < lights.size(); ++i) {
        const Entity e = lights[i];
        const Light* light = world.tryGet<Light>(e);
        const Shadow* shadow = world.tryGet<Shadow>(e);
        const WorldTransform* wt = world.tryGet<WorldTransform>(e);
        if (light == nullptr || shadow == nullptr || wt == nullptr) continue;
        if (shadow->technique == ShadowTechnique::None) continue;
        if (!wt->finite) {
            frame_.warnings.push_back(std::string(lightName(world, e)) +
                                      ": non-finite transform, light skipped");
            continue;
        }
        ShadowLightPlan plan;
        plan.entity = e;
        plan.sceneIndex = static_cast<int>(i);
        plan.name = lightName(world, e);
        plan.light = *light;
        plan.settings = *shadow;
        clampShadowSettings(plan.settings, plan.light, limits_, plan.name, frame_.warnings);
        plan.mapSize = plan.settings.mapSize;
        const LightPose pose = lightPose(*wt);
        plan.affectsView = lightAffectsView(plan.light, pose, cameraFrustum);
        plan.layers = planLayers(plan, pose, camera, geometry);
        markDirty(world, plan);
        frame_.lights.push_back(std::move(plan));
    }
    // Forget lights that are gone so their memory does not grow without bound.
    std::erase_if(memory_, [&](const auto& m) {
        return std::none_of(frame_.lights.begin(), frame_.lights.end(),
                            [&](const ShadowLightPlan& p) { return p.entity == m.first; });
    });
    return frame_;
}

void ShadowPlanner::markDirty(World& world, ShadowLightPlan& plan) {
    auto it = std::find_if(memory_.begin(), memory_.end(),
                           [&](const auto& m) { return m.first == plan.entity; });
    if (it == memory_.end()) {
        memory_.emplace_back(plan.entity, LightMemory{});
        it = std::prev(memory_.end());
    }
    LightMemory& mem = it->second;
    const bool reallocated = mem.mapSize != plan.mapSize || mem.layers.size() != plan.layers.size();
    if (!plan.affectsView) {
        // Nothing the camera sees is lit by it: skip the layers. Casters may move meanwhile,
        // so forget what was drawn; the light is redrawn whole when it matters again.
        for (ShadowLayerPlan& layer : plan.layers) layer.dirty = false;
        mem = LightMemory{};
        return;
    }
    if (reallocated) {
        mem.mapSize = plan.mapSize;
        mem.layers.assign(plan.layers.size(), LayerMemory{});
    }
    for (std::size_t k = 0; k < plan.layers.size(); ++k) {
        ShadowLayerPlan& layer = plan.layers[k];
        LayerMemory& last = mem.layers[k];
        bool dirty = !caching_ || reallocated || last.lightFromWorld != layer.lightFromWorld ||
                     last.clipFromLight != layer.clipFromLight || last.casters != layer.casters;
        for (std::size_t c = 0; !dirty && c < layer.casters.size(); ++c) {
            const WorldTransform* wt = world.tryGet<WorldTransform>(layer.casters[c]);
            dirty = wt == nullptr || wt->movedThisFrame;
        }
        layer.dirty = dirty;
        if (dirty) {
            last.lightFromWorld = layer.lightFromWorld;
            last.clipFromLight = layer.clipFromLight;
            last.casters = layer.casters;
        }
    }
}

}  // namespace shadow
