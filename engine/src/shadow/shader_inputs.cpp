// The public shader contract (shadow_shaders.h): the GLSL text a game compiles and the inputs it
// binds, the same the engine's renderer reads.
#include "shadow/shader_inputs.h"

#include <shadow/shadow_shaders.h>

#include "gl/no_throw.h"
#include "gl/program.h"
#include "gl/technique_glsl.h"
#include "shadow/light_records.h"

#include <stdexcept>
#include <string>
#include <vector>

namespace shadow {
namespace {

/// Throws `std::invalid_argument` when `points` has a negative entry, two blocks on one binding
/// point, or two sampler arrays whose units overlap.
void validate(const ShadowBindingPoints& points) {
    const std::array<std::pair<const char*, int>, 6> all{{{"lightBlock", points.lightBlock},
                                                          {"layerBlock", points.layerBlock},
                                                          {"kernelBlock", points.kernelBlock},
                                                          {"compareUnit", points.compareUnit},
                                                          {"depthUnit", points.depthUnit},
                                                          {"minMaxUnit", points.minMaxUnit}}};
    for (const auto& [name, value] : all) {
        if (value < 0) throw std::invalid_argument(std::string("shadow binding point ") + name + " is negative");
    }
    for (std::size_t a = 0; a < 3; ++a) {
        for (std::size_t b = a + 1; b < 3; ++b) {
            if (all[a].second == all[b].second) {
                throw std::invalid_argument(std::string("shadow binding points ") + all[a].first + " and " +
                                            all[b].first + " are both " + std::to_string(all[a].second));
            }
            const int ua = all[a + 3].second, ub = all[b + 3].second;
            if (ua < ub + SG_MAX_LIGHTS_PER_PASS && ub < ua + SG_MAX_LIGHTS_PER_PASS) {
                throw std::invalid_argument(std::string("shadow texture units ") + all[a + 3].first + " (" +
                                            std::to_string(ua) + ") and " + all[b + 3].first + " (" +
                                            std::to_string(ub) + ") overlap: each array takes " +
                                            std::to_string(SG_MAX_LIGHTS_PER_PASS) + " units");
            }
        }
    }
}

void setupSamplers(const gpu::Sampler& compare, const gpu::Sampler& depth) {
    const float border[4] = {1.0f, 1.0f, 1.0f, 1.0f};  // outside the map: nothing blocks
    for (const gpu::Sampler* smp : {&compare, &depth}) {
        gl.SamplerParameteri(smp->get(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_BORDER);
        gl.SamplerParameteri(smp->get(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_BORDER);
        gl.SamplerParameterfv(smp->get(), GL_TEXTURE_BORDER_COLOR, border);
    }
    // Hardware comparison with linear filtering: every tap is a 2x2 bilinear PCF.
    gl.SamplerParameteri(compare.get(), GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
    gl.SamplerParameteri(compare.get(), GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
    gl.SamplerParameteri(compare.get(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    gl.SamplerParameteri(compare.get(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    gl.SamplerParameteri(depth.get(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    gl.SamplerParameteri(depth.get(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    compare.label("Shadow/compareSampler");
    depth.label("Shadow/depthSampler");
}

}  // namespace

std::string shadowShaderSource(const ShadowBindingPoints& points, unsigned techniques) {
    validate(points);
    std::vector<std::string> defines{
        "SG_BINDING_LIGHTS " + std::to_string(points.lightBlock),
        "SG_BINDING_LAYERS " + std::to_string(points.layerBlock),
        "SG_BINDING_KERNELS " + std::to_string(points.kernelBlock),
        "SG_UNIT_SHADOW_COMPARE " + std::to_string(points.compareUnit),
        "SG_UNIT_SHADOW_DEPTH " + std::to_string(points.depthUnit),
        "SG_UNIT_SHADOW_MINMAX " + std::to_string(points.minMaxUnit),
    };
    // A game's shader never gets the benchmarks' baselines.
    techniques &= kAllShadowTechniques;
    gpu::appendTechniqueDefines(techniques, defines);
    return gpu::expandShaderBody("shadow.glsl", defines, "host shader", techniques).text;
}

Result<std::string> tryShadowShaderSource(const ShadowBindingPoints& points, unsigned techniques) noexcept {
    return gpu::noThrow<std::string>("shadowShaderSource", [&] { return shadowShaderSource(points, techniques); });
}

Result<const ShadowShaderInputs*> ShadowSystem::tryShaderInputs(std::span<const int> sceneLights,
                                                                const glm::dvec3& wsCamera) noexcept {
    return gpu::noThrow<const ShadowShaderInputs*>("shaderInputs",
                                                   [&] { return &shaderInputs(sceneLights, wsCamera); });
}

ShadowSystem::ShaderInputsGpu::ShaderInputsGpu() {
    GLuint s[2] = {0, 0};
    gl.CreateSamplers(2, s);
    compareSampler = gpu::Sampler(s[0]);
    depthSampler = gpu::Sampler(s[1]);
    setupSamplers(compareSampler, depthSampler);
    const std::vector<glm::vec2> disk = gpu::poissonDisk(SG_MAX_SAMPLES);
    kernel =
        gpu::makeBuffer("Shadow/kernels", static_cast<GLsizeiptr>(disk.size() * sizeof(glm::vec2)), disk.data(), 0);
    lights = gpu::makeBuffer("Shadow/shaderInputs/lights", sizeof(lightRecords), nullptr, GL_DYNAMIC_STORAGE_BIT);
    layers = gpu::makeBuffer("Shadow/shaderInputs/layers", sizeof(layerRecords), nullptr, GL_DYNAMIC_STORAGE_BIT);
    inputs.lightBuffer = lights.get();
    inputs.layerBuffer = layers.get();
    inputs.kernelBuffer = kernel.get();
    inputs.compareSampler = compareSampler.get();
    inputs.depthSampler = depthSampler.get();
    gpu::checkGlError("creating the shadow shader inputs");
}

const ShadowShaderInputs& ShadowSystem::shaderInputs(std::span<const int> sceneLights, const glm::dvec3& wsCamera) {
    const ShadowFrame& frame = planner_.frame();
    if (sceneLights.size() > SG_MAX_LIGHTS_PER_PASS) {
        throw std::invalid_argument("shaderInputs: " + std::to_string(sceneLights.size()) + " lights, at most " +
                                    std::to_string(SG_MAX_LIGHTS_PER_PASS) + " per call");
    }
    ShaderInputsGpu& g = *inputs_;
    ShadowShaderInputs& in = g.inputs;
    in.lights = static_cast<int>(sceneLights.size());
    in.sceneLight.fill(-1);
    in.depthArray.fill(0);
    in.minMax.fill(0);
    in.techniques = 0;
    in.type.fill(SG_LIGHT_POINT);
    in.technique.fill(SG_TECH_NONE);
    in.kernel.fill(SG_KERNEL_VOGEL);
    g.lightRecords.fill(gpu::GpuLight{});
    for (std::size_t slot = 0; slot < sceneLights.size(); ++slot) {
        const int light = sceneLights[slot];
        if (light < 0 || static_cast<std::size_t>(light) >= frame.lights.size()) {
            throw std::invalid_argument("shaderInputs: " + std::to_string(light) +
                                        " is not a scene light (the frame has " + std::to_string(frame.lights.size()) +
                                        ")");
        }
        const ShadowLightPlan& plan = frame.lights[static_cast<std::size_t>(light)];
        g.lightRecords[slot] =
            gpu::packSlot(plan, wsCamera, static_cast<int>(slot), &g.layerRecords[slot * SG_MAX_LAYERS_PER_LIGHT]);
        in.sceneLight[slot] = light;
        in.depthArray[slot] = textureOf(static_cast<std::size_t>(light));
        in.minMax[slot] = minMaxOf(static_cast<std::size_t>(light));
        if (plan.hasMap()) in.techniques |= techniqueBit(plan.technique());
        in.type[slot] = g.lightRecords[slot].type;
        in.technique[slot] = g.lightRecords[slot].technique;
        in.kernel[slot] = g.lightRecords[slot].kernel;
    }
    gl.NamedBufferSubData(g.lights.get(), 0, sizeof(g.lightRecords), g.lightRecords.data());
    gl.NamedBufferSubData(g.layers.get(), 0, sizeof(g.layerRecords), g.layerRecords.data());
    gpu::checkGlError("shaderInputs");
    return in;
}

void ShadowSystem::bindShaderInputs(const ShadowShaderInputs& inputs, const ShadowBindingPoints& points) const {
    gl.BindBufferBase(GL_UNIFORM_BUFFER, static_cast<GLuint>(points.lightBlock), inputs.lightBuffer);
    gl.BindBufferBase(GL_UNIFORM_BUFFER, static_cast<GLuint>(points.layerBlock), inputs.layerBuffer);
    bindShadowResources(std::span<const int>(inputs.sceneLight.data(), static_cast<std::size_t>(inputs.lights)),
                        points);
}

void ShadowSystem::bindShadowResources(std::span<const int> sceneLights, const ShadowBindingPoints& points) const {
    const ShaderInputsGpu& g = *inputs_;
    gl.BindBufferBase(GL_UNIFORM_BUFFER, static_cast<GLuint>(points.kernelBlock), g.kernel.get());
    for (int slot = 0; slot < SG_MAX_LIGHTS_PER_PASS; ++slot) {
        const auto s = static_cast<std::size_t>(slot);
        const int light = s < sceneLights.size() ? sceneLights[s] : -1;
        const auto i = static_cast<std::size_t>(light);
        const GLuint texture = light >= 0 ? textureOf(i) : 0u;
        gl.BindTextureUnit(static_cast<GLuint>(points.compareUnit + slot), texture);
        gl.BindSampler(static_cast<GLuint>(points.compareUnit + slot), g.compareSampler.get());
        gl.BindTextureUnit(static_cast<GLuint>(points.depthUnit + slot), texture);
        gl.BindSampler(static_cast<GLuint>(points.depthUnit + slot), g.depthSampler.get());
        gl.BindTextureUnit(static_cast<GLuint>(points.minMaxUnit + slot), light >= 0 ? minMaxOf(i) : 0u);
        // The texture's own filtering: nearest per level for a pyramid, trilinear for moments.
        gl.BindSampler(static_cast<GLuint>(points.minMaxUnit + slot), 0);
    }
}

}  // namespace shadow
