#include "shadow/shader_records.h"

#include "core/light_records.h"

#include <stdexcept>
#include <string>

namespace shadow::gpu {

ShaderRecords::ShaderRecords(const ShaderResources& resources, std::string_view label) {
    const std::string prefix(label);
    lights = makeBuffer(prefix + "/lights", sizeof(lightRecords), nullptr, GL_DYNAMIC_STORAGE_BIT);
    layers = makeBuffer(prefix + "/layers", sizeof(layerRecords), nullptr, GL_DYNAMIC_STORAGE_BIT);
    inputs.lightBuffer = GlBuffer{lights.get()};
    inputs.layerBuffer = GlBuffer{layers.get()};
    inputs.kernelBuffer = GlBuffer{resources.kernel.get()};
    inputs.compareSampler = GlSampler{resources.compareSampler.get()};
    inputs.depthSampler = GlSampler{resources.depthSampler.get()};
    checkGlError("creating " + prefix);
}

const ShadowShaderInputs& uploadShaderInputs(ShaderRecords& records, const ShadowFrame& frame, const ShadowMaps& maps,
                                             std::span<const int> sceneLights, const glm::dvec3& wsCamera,
                                             std::string_view call) {
    if (sceneLights.size() > SG_MAX_LIGHTS_PER_PASS) {
        throw std::invalid_argument(std::string(call) + ": " + std::to_string(sceneLights.size()) +
                                    " lights, at most " + std::to_string(SG_MAX_LIGHTS_PER_PASS) + " per call");
    }
    ShadowShaderInputs& in = records.inputs;
    in.lights = static_cast<int>(sceneLights.size());
    in.sceneLight.fill(-1);
    in.depthArray.fill(GlTexture{});
    in.minMax.fill(GlTexture{});
    in.techniques = 0;
    in.type.fill(SG_LIGHT_POINT);
    in.technique.fill(SG_TECH_NONE);
    in.kernel.fill(SG_KERNEL_VOGEL);
    records.lightRecords.fill(GpuLight{});
    for (std::size_t slot = 0; slot < sceneLights.size(); ++slot) {
        const int light = sceneLights[slot];
        if (light < 0 || static_cast<std::size_t>(light) >= frame.lights.size()) {
            throw std::invalid_argument(std::string(call) + ": " + std::to_string(light) +
                                        " is not a scene light (the frame has " + std::to_string(frame.lights.size()) +
                                        ")");
        }
        const ShadowLightPlan& plan = frame.lights[static_cast<std::size_t>(light)];
        GpuLight& record = records.lightRecords[slot];
        record =
            packSlot(plan, wsCamera, static_cast<int>(slot), &records.layerRecords[slot * SG_MAX_LAYERS_PER_LIGHT]);
        in.sceneLight[slot] = light;
        in.depthArray[slot] = maps.textureOf(static_cast<std::size_t>(light));
        in.minMax[slot] = maps.filterChainOf(static_cast<std::size_t>(light));
        if (plan.hasMap()) in.techniques |= techniqueBit(plan.technique());
        in.type[slot] = record.type;
        in.technique[slot] = record.technique;
        in.kernel[slot] = record.kernel;
    }
    // The distance fields, positions relative to this call's camera (the same for every slot).
    in.fieldAtlas = maps.fieldAtlas();
    in.fieldInstances = (in.techniques & techniqueBit(ShadowTechnique::Sdf)) != 0 ? maps.fieldInstances(wsCamera)
                                                                                  : maps.fieldInstances();
    gl.NamedBufferSubData(records.lights.get(), 0, sizeof(records.lightRecords), records.lightRecords.data());
    gl.NamedBufferSubData(records.layers.get(), 0, sizeof(records.layerRecords), records.layerRecords.data());
    checkGlError(call);
    return in;
}

void bindShaderInputs(const ShaderResources& resources, const ShadowMaps& maps, const ShadowShaderInputs& inputs,
                      const ShadowBindingPoints& points) {
    gl.BindBufferBase(GL_UNIFORM_BUFFER, static_cast<GLuint>(points.lightBlock), inputs.lightBuffer.name);
    gl.BindBufferBase(GL_UNIFORM_BUFFER, static_cast<GLuint>(points.layerBlock), inputs.layerBuffer.name);
    bindShadowResources(resources, maps,
                        std::span<const int>(inputs.sceneLight.data(), static_cast<std::size_t>(inputs.lights)),
                        points);
}

}  // namespace shadow::gpu
