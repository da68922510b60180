// The public shader contract (shadow_shaders.h, shader_contract.h): the GLSL text a game
// compiles and the inputs it binds, the same the engine's renderer reads.
#include <shadow/shader_contract.h>
#include <shadow/shadow_shaders.h>

#include "core/light_records.h"
#include "core/shader_resources.h"
#include "gl/gl_state.h"
#include "gl/no_throw.h"
#include "gl/program.h"
#include "gl/technique_glsl.h"
#include "shadow/shader_records.h"

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
    // The distance-field technique's two units: not negative, apart, and outside the arrays.
    const std::array<std::pair<const char*, int>, 2> single{
        {{"sdfAtlasUnit", points.sdfAtlasUnit}, {"sdfInstanceUnit", points.sdfInstanceUnit}}};
    for (const auto& [name, unit] : single) {
        if (unit < 0) throw std::invalid_argument(std::string("shadow binding point ") + name + " is negative");
        for (std::size_t a = 3; a < all.size(); ++a) {
            if (unit >= all[a].second && unit < all[a].second + SG_MAX_LIGHTS_PER_PASS) {
                throw std::invalid_argument(std::string("shadow texture unit ") + name + " (" + std::to_string(unit) +
                                            ") lies in " + all[a].first + "'s " +
                                            std::to_string(SG_MAX_LIGHTS_PER_PASS) + " units");
            }
        }
    }
    if (points.sdfAtlasUnit == points.sdfInstanceUnit) {
        throw std::invalid_argument("shadow texture units sdfAtlasUnit and sdfInstanceUnit are both " +
                                    std::to_string(points.sdfAtlasUnit));
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
        "SG_UNIT_SDF_ATLAS " + std::to_string(points.sdfAtlasUnit),
        "SG_UNIT_SDF_INSTANCES " + std::to_string(points.sdfInstanceUnit),
    };
    // A game's shader never gets the benchmarks' baselines.
    techniques &= kAllShadowTechniques;
    gpu::appendTechniqueDefines(techniques, defines);
    return gpu::expandShaderBody("shadow.glsl", defines, "host shader", techniques).text;
}

Result<std::string> tryShadowShaderSource(const ShadowBindingPoints& points, unsigned techniques) noexcept {
    return gpu::noThrow<std::string>("shadowShaderSource", [&] { return shadowShaderSource(points, techniques); });
}

struct ShadowShaderContract::Impl {
    gpu::ShaderResources resources;
    gpu::ShaderRecords records{resources, "Shadow/shaderInputs"};
    std::vector<Warning> pending;  ///< see `warnings`
};

ShadowShaderContract::ShadowShaderContract() {
    gpu::requireLoaded("ShadowShaderContract");
    // Before the objects are made, so that the host's error is reported, not thrown.
    std::vector<Warning> pending;
    gpu::reportHostGlErrors("ShadowShaderContract", pending, gpu::kMaxPendingWarnings);
    impl_ = std::make_unique<Impl>();
    impl_->pending = std::move(pending);
}

ShadowShaderContract::~ShadowShaderContract() = default;

Result<std::unique_ptr<ShadowShaderContract>> ShadowShaderContract::create() noexcept {
    return gpu::noThrow<std::unique_ptr<ShadowShaderContract>>("ShadowShaderContract",
                                                               [] { return std::make_unique<ShadowShaderContract>(); });
}

const ShadowShaderInputs& ShadowShaderContract::inputs(const ShadowFrame& frame, const ShadowMaps& maps,
                                                       std::span<const int> sceneLights, const glm::dvec3& wsCamera) {
    gpu::reportHostGlErrors("ShadowShaderContract::inputs", impl_->pending, gpu::kMaxPendingWarnings);
    return gpu::uploadShaderInputs(impl_->records, frame, maps, sceneLights, wsCamera, "shaderInputs");
}

Result<const ShadowShaderInputs*> ShadowShaderContract::tryInputs(const ShadowFrame& frame, const ShadowMaps& maps,
                                                                  std::span<const int> sceneLights,
                                                                  const glm::dvec3& wsCamera) noexcept {
    return gpu::noThrow<const ShadowShaderInputs*>("shaderInputs",
                                                   [&] { return &inputs(frame, maps, sceneLights, wsCamera); });
}

void ShadowShaderContract::bind(const ShadowShaderInputs& inputs, const ShadowBindingPoints& points) {
    gpu::reportHostGlErrors("ShadowShaderContract::bind", impl_->pending, gpu::kMaxPendingWarnings);
    // The maps are those the inputs name: bind them by name, whatever maps object made them.
    // Binding an indexed point binds the generic GL_UNIFORM_BUFFER too: the host's is put back.
    GLint generic = 0;
    gl.GetIntegerv(GL_UNIFORM_BUFFER_BINDING, &generic);
    gl.BindBufferBase(GL_UNIFORM_BUFFER, static_cast<GLuint>(points.lightBlock), inputs.lightBuffer.name);
    gl.BindBufferBase(GL_UNIFORM_BUFFER, static_cast<GLuint>(points.layerBlock), inputs.layerBuffer.name);
    gl.BindBufferBase(GL_UNIFORM_BUFFER, static_cast<GLuint>(points.kernelBlock), inputs.kernelBuffer.name);
    gl.BindBuffer(GL_UNIFORM_BUFFER, static_cast<GLuint>(generic));
    for (int slot = 0; slot < SG_MAX_LIGHTS_PER_PASS; ++slot) {
        const auto s = static_cast<std::size_t>(slot);
        const bool used = slot < inputs.lights;
        const GLuint texture = used ? inputs.depthArray[s].name : 0u;
        gl.BindTextureUnit(static_cast<GLuint>(points.compareUnit + slot), texture);
        gl.BindSampler(static_cast<GLuint>(points.compareUnit + slot), inputs.compareSampler.name);
        gl.BindTextureUnit(static_cast<GLuint>(points.depthUnit + slot), texture);
        gl.BindSampler(static_cast<GLuint>(points.depthUnit + slot), inputs.depthSampler.name);
        gl.BindTextureUnit(static_cast<GLuint>(points.minMaxUnit + slot), used ? inputs.minMax[s].name : 0u);
        // The texture's own filtering: nearest per level for a pyramid, trilinear for moments.
        gl.BindSampler(static_cast<GLuint>(points.minMaxUnit + slot), 0);
    }
    // The distance-field units only when some light of the inputs marches fields: without an sdf
    // light the host's units (26-27 by default) stay as they are.
    if ((inputs.techniques & techniqueBit(ShadowTechnique::Sdf)) == 0) return;
    gl.BindTextureUnit(static_cast<GLuint>(points.sdfAtlasUnit), inputs.fieldAtlas.name);
    gl.BindSampler(static_cast<GLuint>(points.sdfAtlasUnit), 0);
    gl.BindTextureUnit(static_cast<GLuint>(points.sdfInstanceUnit), inputs.fieldInstances.name);
    gl.BindSampler(static_cast<GLuint>(points.sdfInstanceUnit), 0);
}

void ShadowShaderContract::bindResources(const ShadowMaps& maps, std::span<const int> sceneLights,
                                         const ShadowBindingPoints& points) {
    gpu::reportHostGlErrors("ShadowShaderContract::bindResources", impl_->pending, gpu::kMaxPendingWarnings);
    gpu::bindShadowResources(impl_->resources, maps, sceneLights, points);
}

const std::vector<Warning>& ShadowShaderContract::warnings() const { return impl_->pending; }

void ShadowShaderContract::clearWarnings() { impl_->pending.clear(); }

}  // namespace shadow
