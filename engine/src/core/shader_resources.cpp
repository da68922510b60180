#include "core/shader_resources.h"

#include "core/light_records.h"

#include <glm/glm.hpp>

#include <vector>

namespace shadow::gpu {

ShaderResources::ShaderResources() {
    GLuint s[2] = {0, 0};
    gl.CreateSamplers(2, s);
    compareSampler = Sampler(s[0]);
    depthSampler = Sampler(s[1]);
    const float border[4] = {1.0f, 1.0f, 1.0f, 1.0f};  // outside the map: nothing blocks
    for (const Sampler* smp : {&compareSampler, &depthSampler}) {
        gl.SamplerParameteri(smp->get(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_BORDER);
        gl.SamplerParameteri(smp->get(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_BORDER);
        gl.SamplerParameterfv(smp->get(), GL_TEXTURE_BORDER_COLOR, border);
    }
    // Hardware comparison with linear filtering: every tap is a 2x2 bilinear PCF.
    gl.SamplerParameteri(compareSampler.get(), GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
    gl.SamplerParameteri(compareSampler.get(), GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
    gl.SamplerParameteri(compareSampler.get(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    gl.SamplerParameteri(compareSampler.get(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    gl.SamplerParameteri(depthSampler.get(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    gl.SamplerParameteri(depthSampler.get(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    compareSampler.label("Shadow/compareSampler");
    depthSampler.label("Shadow/depthSampler");
    const std::vector<glm::vec2> disk = poissonDisk(SG_MAX_SAMPLES);
    kernel = makeBuffer("Shadow/kernels", static_cast<GLsizeiptr>(disk.size() * sizeof(glm::vec2)), disk.data(), 0);
    checkGlError("creating the shadow samplers and kernel");
}

void bindShadowResources(const ShaderResources& resources, const ShadowMaps& maps, std::span<const int> sceneLights,
                         const ShadowBindingPoints& points) {
    gl.BindBufferBase(GL_UNIFORM_BUFFER, static_cast<GLuint>(points.kernelBlock), resources.kernel.get());
    for (int slot = 0; slot < SG_MAX_LIGHTS_PER_PASS; ++slot) {
        const auto s = static_cast<std::size_t>(slot);
        const int light = s < sceneLights.size() ? sceneLights[s] : -1;
        const auto i = static_cast<std::size_t>(light);
        const GLuint texture = light >= 0 ? maps.textureOf(i).name : 0u;
        gl.BindTextureUnit(static_cast<GLuint>(points.compareUnit + slot), texture);
        gl.BindSampler(static_cast<GLuint>(points.compareUnit + slot), resources.compareSampler.get());
        gl.BindTextureUnit(static_cast<GLuint>(points.depthUnit + slot), texture);
        gl.BindSampler(static_cast<GLuint>(points.depthUnit + slot), resources.depthSampler.get());
        gl.BindTextureUnit(static_cast<GLuint>(points.minMaxUnit + slot), light >= 0 ? maps.filterChainOf(i).name : 0u);
        // The texture's own filtering: nearest per level for a pyramid, trilinear for moments.
        gl.BindSampler(static_cast<GLuint>(points.minMaxUnit + slot), 0);
    }
    // Technique sdf: the fields, and their instances as last uploaded for the caller's camera.
    gl.BindTextureUnit(static_cast<GLuint>(points.sdfAtlasUnit), maps.fieldAtlas().name);
    gl.BindSampler(static_cast<GLuint>(points.sdfAtlasUnit), 0);
    gl.BindTextureUnit(static_cast<GLuint>(points.sdfInstanceUnit), maps.fieldInstances().name);
    gl.BindSampler(static_cast<GLuint>(points.sdfInstanceUnit), 0);
}

}  // namespace shadow::gpu
