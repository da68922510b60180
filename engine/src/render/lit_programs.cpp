#include "render/lit_programs.h"

#include <shadow/components.h>

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
    m.skinned = gl.GetUniformLocation(program, "uSkinned");
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
    return m;
}

LitProgram buildLit(const LitVariant& variant) {
    LitProgram p;
    // The deferred variant reads its lights' visibility: it compiles no technique.
    p.program = gpu::buildProgram({variantLabel(variant), variant.deferred ? "fullscreen.vert.glsl" : "lit.vert.glsl",
                                   "lit.frag.glsl", variantDefines(variant),
                                   variant.deferred ? 0u : variantTechniques(variant)});
    const GLuint id = p.program.get();
    p.mesh = meshUniforms(id);
    p.material = materialUniforms(id);
    p.ambient = gl.GetUniformLocation(id, "uAmbient");
    p.cameraForward = gl.GetUniformLocation(id, "uCameraForward");
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
    if (v.debugView != SG_DEBUG_NONE) name += ",debug" + std::to_string(v.debugView);
    return "Main/Lit[" + name + "]";
}

unsigned variantTechniques(const LitVariant& v) {
    unsigned used = 0;
    for (int i = 0; i < v.lights; ++i) used |= 1u << static_cast<unsigned>(v.technique[static_cast<std::size_t>(i)]);
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
        defines.emplace_back("SG_FULLSCREEN_FAR");  // depth-tested: only the surfaces' pixels run
    } else {
        gpu::appendTechniqueDefines(variantTechniques(v), defines);
    }
    if (v.aovs) defines.emplace_back("SG_WRITE_AOVS");
    if (v.debugView != SG_DEBUG_NONE) {
        defines.emplace_back("SG_DEBUG_VIEWS");
        defines.push_back("SG_DEBUG_VIEW " + std::to_string(v.debugView));
        defines.push_back("SG_DEBUG_SLOT " + std::to_string(v.debugSlot));
    }
    return defines;
}

LitProgram& LitProgramCache::get(const LitVariant& variant, int& compiled) {
    auto it = programs_.find(variant);
    if (it == programs_.end()) {
        it = programs_.emplace(variant, buildLit(variant)).first;
        ++compiled;
    }
    return it->second;
}

DepthPrepassProgram buildDepthPrepass(bool alphaTested) {
    DepthPrepassProgram p;
    p.program = gpu::buildProgram(
        {alphaTested ? "Main/DepthPrepass/alpha" : "Main/DepthPrepass", "lit.vert.glsl", "depth_prepass.frag.glsl",
         alphaTested ? std::vector<std::string>{"SG_ALPHA_TESTED"} : std::vector<std::string>{}});
    p.mesh = meshUniforms(p.program.get());
    p.alpha = gl.GetUniformLocation(p.program.get(), "uAlpha");
    p.alphaCutoff = gl.GetUniformLocation(p.program.get(), "uAlphaCutoff");
    return p;
}

SurfaceProgram buildSurfaceProgram(bool alphaTested) {
    SurfaceProgram p;
    p.program =
        gpu::buildProgram({alphaTested ? "Main/Surfaces/alpha" : "Main/Surfaces", "lit.vert.glsl", "gbuffer.frag.glsl",
                           alphaTested ? std::vector<std::string>{"SG_ALPHA_TESTED"} : std::vector<std::string>{}});
    const GLuint id = p.program.get();
    p.mesh = meshUniforms(id);
    p.material = materialUniforms(id);
    p.alpha = gl.GetUniformLocation(id, "uAlpha");
    p.alphaCutoff = gl.GetUniformLocation(id, "uAlphaCutoff");
    return p;
}

}  // namespace shadow::render
