#include "render/lit_programs.h"

#include <shadow/components.h>

#include "gl/mesh_cache_access.h"
#include "gl/program.h"
#include "gl/technique_glsl.h"

#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <array>
#include <span>
#include <cmath>

namespace shadow::render {
namespace {

const char* typeLabel(int type) { return lightTypeName(static_cast<LightType>(type)); }

MeshUniforms meshUniforms(GLuint program) {
    MeshUniforms m;
    m.csFromLocal = gl.GetUniformLocation(program, "uCsFromLocal");
    m.normalFromLocal = gl.GetUniformLocation(program, "uNormalFromLocal");
    m.clipFromCs = gl.GetUniformLocation(program, "uClipFromCs");
    m.deform = gpu::DeformUniforms::of(program);
    return m;
}

MaterialUniforms materialUniforms(GLuint program) {
    MaterialUniforms m;
    m.receiveShadows = gl.GetUniformLocation(program, "uReceiveShadows");
    m.albedo = gl.GetUniformLocation(program, "uAlbedo");
    m.specular = gl.GetUniformLocation(program, "uSpecular");
    m.shininess = gl.GetUniformLocation(program, "uShininess");
    m.metallic = gl.GetUniformLocation(program, "uMetallic");
    m.textured = gl.GetUniformLocation(program, "uTextured");
    m.emissive = gl.GetUniformLocation(program, "uEmissive");
    m.baseFactor = gl.GetUniformLocation(program, "uBaseFactor");
    m.roughness = gl.GetUniformLocation(program, "uRoughness");
    m.normalScale = gl.GetUniformLocation(program, "uNormalScale");
    m.occlusionStrength = gl.GetUniformLocation(program, "uOcclusionStrength");
    m.mapUsed = gl.GetUniformLocation(program, "uMapUsed");
    m.mapSet = gl.GetUniformLocation(program, "uMapSet");
    m.mapTransform = gl.GetUniformLocation(program, "uMapTransform");
    return m;
}

/// The maps variant's maps in SG_MAP_* order (material.glsl).
std::array<const MaterialMap*, 4> mapsOf(const Material& m) {
    return {&m.metallicRoughnessMap, &m.normalMap, &m.occlusionMap, &m.emissiveMap};
}

/// The maps variant's per-map uniforms.
void setMaps(GLuint program, const MaterialUniforms& u, const Material& material) {
    std::array<GLint, 4> used{}, set{};
    std::array<glm::mat3x2, 4> transform{};
    const auto maps = mapsOf(material);
    for (std::size_t i = 0; i < maps.size(); ++i) {
        used[i] = maps[i]->texture != nullptr ? 1 : 0;
        set[i] = maps[i]->texcoordSet == 1 ? 1 : 0;
        transform[i] = maps[i]->uvTransform;
    }
    gl.ProgramUniform1iv(program, u.mapUsed, 4, used.data());
    gl.ProgramUniform1iv(program, u.mapSet, 4, set.data());
    gl.ProgramUniformMatrix3x2fv(program, u.mapTransform, 4, GL_FALSE, glm::value_ptr(transform[0]));
    gl.ProgramUniform3fv(program, u.baseFactor, 1, glm::value_ptr(glm::clamp(material.baseColor, 0.0f, 1.0f)));
    gl.ProgramUniform1f(program, u.roughness, std::clamp(material.roughness, 0.0f, 1.0f));
    gl.ProgramUniform1f(program, u.normalScale, material.normalScale);
    gl.ProgramUniform1f(program, u.occlusionStrength, std::clamp(material.occlusionStrength, 0.0f, 1.0f));
}

/// Whether the group of four slots `layer` of a variant marks its lights one by one for the
/// correction (`refinesPerLight`), or all of them where one is.
bool marksPerLight(const LitVariant& v, int layer) {
    const int first = 4 * layer;
    return refinesPerLight(v, first, std::clamp(v.lights - first, 0, 4));
}

/// Whether a variant's program runs its lights' techniques: forward, or a deferred pass's
/// correction.
bool runsTechniques(const LitVariant& v) { return !v.deferred || v.correction; }

LitProgram buildLit(const LitVariant& variant) {
    LitProgram p;
    // The deferred variant reads its lights' visibility: it compiles no technique, unless it is
    // the correction that recomputes the lights the lit pass marked.
    p.program = gpu::buildProgram({variantLabel(variant), variant.deferred ? "fullscreen.vert.glsl" : "lit.vert.glsl",
                                   "lit.frag.glsl", variantDefines(variant),
                                   runsTechniques(variant) ? variantTechniques(variant) : 0u});
    const GLuint id = p.program.get();
    p.mesh = meshUniforms(id);
    p.material = materialUniforms(id);
    p.ambientSky = gl.GetUniformLocation(id, "uAmbientSky");
    p.ambientGround = gl.GetUniformLocation(id, "uAmbientGround");
    p.cameraForward = gl.GetUniformLocation(id, "uCameraForward");
    p.ray00 = gl.GetUniformLocation(id, "uRay00");
    p.rayDx = gl.GetUniformLocation(id, "uRayDx");
    p.rayDy = gl.GetUniformLocation(id, "uRayDy");
    p.pixelAngle = gl.GetUniformLocation(id, "uPixelAngle");
    p.countSlots = gl.GetUniformLocation(id, "uCountSlots");
    p.countBase = gl.GetUniformLocation(id, "uCountBase");
    return p;
}

}  // namespace

void setMaterial(GLuint program, const MaterialUniforms& u, const Mesh& mesh, const Material& material) {
    gl.ProgramUniform1i(program, u.receiveShadows, mesh.receiveShadows ? 1 : 0);
    gl.ProgramUniform3fv(program, u.albedo, 1, glm::value_ptr(material.albedo));
    gl.ProgramUniform3fv(program, u.specular, 1, glm::value_ptr(material.specular));
    gl.ProgramUniform1f(program, u.shininess, std::clamp(material.shininess, 1.0f, 4096.0f));
    gl.ProgramUniform1f(program, u.metallic, std::clamp(material.metallic, 0.0f, 1.0f));
    gl.ProgramUniform1i(program, u.textured, material.baseColorTexture != nullptr ? 1 : 0);
    gl.ProgramUniform3fv(program, u.emissive, 1, glm::value_ptr(glm::clamp(material.emissive, 0.0f, 1e6f)));
    if (u.mapUsed >= 0) setMaps(program, u, material);
}

void bindMaterialTextures(MeshCache& meshes, const Material& material, bool maps) {
    gpu::MeshCacheAccess::bindTexture(meshes, material.baseColorTexture, SG_UNIT_BASE_COLOR);
    if (!maps) return;
    const auto all = mapsOf(material);
    const std::array<unsigned, 4> units{SG_UNIT_METALLIC_ROUGHNESS, SG_UNIT_NORMAL_MAP, SG_UNIT_OCCLUSION,
                                        SG_UNIT_EMISSIVE};
    for (std::size_t i = 0; i < all.size(); ++i) {
        // Colour in sRGB (emission), data linear (metallic-roughness, normals, occlusion).
        gpu::MeshCacheAccess::bindTexture(meshes, all[i]->texture, units[i], i == 3);
    }
}

std::string variantLabel(const LitVariant& v) {
    std::string name;
    for (int i = 0; i < v.lights; ++i) {
        if (!name.empty()) name += ',';
        name += typeLabel(v.type[static_cast<std::size_t>(i)]);
        name += ':';
        name += techniqueName(static_cast<ShadowTechnique>(v.technique[static_cast<std::size_t>(i)]));
    }
    if (v.aovs) name += name.empty() ? "AOV" : ",AOV";
    if (v.deferred) name += name.empty() ? "deferred" : ",deferred";
    for (std::size_t k = 0; k < v.resolve.size(); ++k) {
        if (v.resolve[k] > 1) name += ",resolve" + std::to_string(k) + "/" + std::to_string(v.resolve[k]);
    }
    if (v.correction) {
        name += ",correction";
        if (v.slotBase > 0) name.append("@").append(std::to_string(v.slotBase));
    }
    if (v.materialMaps) name += name.empty() ? "maps" : ",maps";
    if (v.countEdges) name += name.empty() ? "edges" : ",edges";
    if (!v.ambient && !v.correction) name += name.empty() ? "added" : ",added";
    if (!v.textured && !v.deferred) name += name.empty() ? "untextured" : ",untextured";
    if (v.debugView != SG_DEBUG_NONE) name += ",debug" + std::to_string(v.debugView);
    return "Main/Lit[" + name + "]" + gpu::deformLabel(v.deform);
}

unsigned variantTechniques(const LitVariant& v) {
    unsigned used = 0;
    for (int i = 0; i < v.lights; ++i) used |= 1u << static_cast<unsigned>(v.technique[static_cast<std::size_t>(i)]);
    if (v.countEdges) used |= techniqueBit(ShadowTechnique::Hard);  // the count's own hard lookup
    return used;
}

std::vector<std::string> variantDefines(const LitVariant& v) {
    std::vector<std::string> defines;
    defines.push_back("SG_PASS_LIGHTS " + std::to_string(v.lights));
    std::array<gpu::SlotConfig, SG_MAX_LIGHTS_PER_PASS> slots{};
    for (int i = 0; i < v.lights; ++i) {
        const auto k = static_cast<std::size_t>(i);
        slots[k] = {v.type[k], v.technique[k], v.kernel[k]};
    }
    gpu::appendSlotGroupDefines(
        std::span(slots).first(static_cast<std::size_t>(std::clamp(v.lights, 0, SG_MAX_LIGHTS_PER_PASS))),
        SG_MAX_LIGHTS_PER_PASS, defines);
    if (v.deferred) {
        defines.emplace_back("SG_DEFERRED");
        defines.emplace_back("SG_READS_GBUFFER");
        // Depth-tested: only the surfaces' pixels run (GREATER than the scene's depth, at the far
        // plane); the correction's, only the marked ones (GREATER than their mark, 0).
        if (!v.correction) defines.emplace_back("SG_FULLSCREEN_FAR");
        for (std::size_t k = 0; k < v.resolve.size(); ++k) {
            if (v.resolve[k] <= 1) continue;  // read from the stage's full-resolution target
            const std::string layer = "SG_LAYER" + std::to_string(k);
            defines.push_back(layer + "_RESOLVE " + std::to_string(v.resolve[k]));
            defines.push_back(layer + "_PER_LIGHT " + std::to_string(marksPerLight(v, static_cast<int>(k)) ? 1 : 0));
        }
        if (v.correction) {
            defines.emplace_back("SG_LIT_CORRECTION");
            defines.push_back("SG_SLOT_BASE " + std::to_string(v.slotBase));
            // Whole-group marks: every light is marked where the correction runs.
            if (!marksPerLight(v, 0)) defines.emplace_back("SG_LIT_CORRECTION_ALL");
        }
    }
    if (runsTechniques(v)) gpu::appendTechniqueDefines(variantTechniques(v), defines);
    if (v.materialMaps) defines.emplace_back(v.deferred ? "SG_GBUFFER_MATERIAL" : "SG_MATERIAL_MAPS");
    if (v.aovs) defines.emplace_back("SG_WRITE_AOVS");
    if (v.countEdges) defines.emplace_back("SG_COUNT_EDGES");
    if (v.ambient) defines.emplace_back("SG_LIT_AMBIENT");
    if (v.textured && !v.deferred) defines.emplace_back("SG_BASE_COLOR_TEXTURE");
    gpu::appendDeformDefines(v.deform, defines);
    if (v.debugView != SG_DEBUG_NONE) {
        defines.emplace_back("SG_DEBUG_VIEWS");
        defines.push_back("SG_DEBUG_VIEW " + std::to_string(v.debugView));
        defines.push_back("SG_DEBUG_SLOT " + std::to_string(v.debugSlot));
    }
    return defines;
}

LitVariant correctionVariant(const LitVariant& pass, int group) {
    const int first = 4 * group;
    LitVariant c = slotsVariant(pass, first, std::clamp(pass.lights - first, 0, 4));
    c.aovs = pass.aovs;
    c.deferred = true;
    c.materialMaps = pass.materialMaps;
    c.correction = true;
    c.slotBase = static_cast<std::uint8_t>(first);
    c.ambient = false;  // the lit pass added it
    return c;
}

LitProgram& LitProgramCache::get(const LitVariant& variant, int& compiled) {
    auto it = programs_.find(variant);
    if (it == programs_.end()) {
        it = programs_.emplace(variant, buildLit(variant)).first;
        ++compiled;
    }
    return it->second;
}

DepthPrepassProgram buildDepthPrepass(bool alphaTested, unsigned deform) {
    DepthPrepassProgram p;
    std::vector<std::string> defines;
    std::string label = alphaTested ? "Main/DepthPrepass/alpha" : "Main/DepthPrepass";
    if (alphaTested) defines.emplace_back("SG_ALPHA_TESTED");
    label += gpu::deformLabel(deform);
    gpu::appendDeformDefines(deform, defines);
    p.program = gpu::buildProgram({label, "lit.vert.glsl", "depth_prepass.frag.glsl", defines});
    p.mesh = meshUniforms(p.program.get());
    p.alpha = gl.GetUniformLocation(p.program.get(), "uAlpha");
    p.alphaCutoff = gl.GetUniformLocation(p.program.get(), "uAlphaCutoff");
    return p;
}

SurfaceProgram buildSurfaceProgram(unsigned bits) {
    SurfaceProgram p;
    std::string label = "Main/Surfaces";
    std::vector<std::string> defines;
    if ((bits & kSurfaceAlphaTested) != 0) {
        label += "/alpha";
        defines.emplace_back("SG_ALPHA_TESTED");
    }
    if ((bits & kSurfaceMaps) != 0) {
        label += "/maps";
        defines.emplace_back("SG_MATERIAL_MAPS");
    }
    if ((bits & kSurfaceMaterialTargets) != 0) {
        label += "/material";
        defines.emplace_back("SG_GBUFFER_MATERIAL");
    }
    if ((bits & kSurfaceTextured) != 0) {
        label += "/textured";
        defines.emplace_back("SG_BASE_COLOR_TEXTURE");
    }
    label += gpu::deformLabel(bits / kSurfaceDeformUnit);
    gpu::appendDeformDefines(bits / kSurfaceDeformUnit, defines);
    p.program = gpu::buildProgram({label, "lit.vert.glsl", "gbuffer.frag.glsl", defines});
    const GLuint id = p.program.get();
    p.mesh = meshUniforms(id);
    p.material = materialUniforms(id);
    p.alpha = gl.GetUniformLocation(id, "uAlpha");
    p.alphaCutoff = gl.GetUniformLocation(id, "uAlphaCutoff");
    p.cameraForward = gl.GetUniformLocation(id, "uCameraForward");
    return p;
}

}  // namespace shadow::render
