// A game embedding the shadow engine module, in miniature (README.md, "Embedding"). The host
// owns the OpenGL context, the geometry it draws and its shader; the module owns the scene's
// shadow maps and the GLSL that reads them. Step by step, the host
//   1. creates its own OSMesa OpenGL 4.5 core context, loads its own GL table and hands the
//      module the same getProcAddress;
//   2. builds a ground, a box and a post under three lights (a PCSS spot, a PCF point light, a
//      hard-shadowed sun with cascades) with the module's scene API;
//   3. lets the module decide (`prepare`) and draw (`render`) the shadow maps, and renders the
//      frame with the module's own renderer and its visibility AOVs, as shadow_render does: the
//      reference;
//   4. draws the same meshes from its own vertex buffers with its own program, whose fragment
//      shader includes the module's public GLSL (`shadow.glsl`, read from the module's shader
//      directory, the installed copy when it comes as a package, with the host's own include
//      expander and its own binding points), fed by `ShadowSystem::shaderInputs`;
//   5. compares the two visibilities of every light on every covered pixel: they must agree
//      within 1/255, and each light must both shadow and light some pixels.
// Exit code 0 when all of this holds, 1 otherwise (with a message on stderr). Built without
// exceptions, as many games are: the module's headers compile so, and its calls used here
// return their errors as values (`ShadowSystem::create`, `tryRender`, `tryShaderInputs`).
#define GL_GLEXT_PROTOTYPES 1  // declarations only, for the types of the host's GL table below
#include <GL/osmesa.h>

#include <shadow/context.h>
#include <shadow/renderer.h>
#include <shadow/scene.h>
#include <shadow/shadow_system.h>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdint>
#include <fstream>
#include <memory>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace {

// The host's GL table, filled through OSMesaGetProcAddress as a game's loader would (libOSMesa
// does not export the 4.5 entry points as symbols). clang-format would spread the list over
// staircase lines.
// clang-format off
#define HOST_GL_FUNCTIONS(X)                                                                             \
    X(AttachShader) X(BindFramebuffer) X(BindVertexArray) X(ClearNamedFramebufferfv) X(ColorMask)      \
    X(CompileShader) X(CreateBuffers) X(CreateFramebuffers) X(CreateProgram) X(CreateShader)            \
    X(CreateTextures) X(CreateVertexArrays) X(DeleteBuffers) X(DeleteFramebuffers) X(DeleteProgram)     \
    X(DeleteShader) X(DeleteTextures) X(DeleteVertexArrays) X(DepthFunc) X(DepthMask) X(Disable)        \
    X(DrawElements) X(Enable) X(EnableVertexArrayAttrib) X(GetError) X(GetProgramiv) X(GetShaderInfoLog) \
    X(GetShaderiv) X(GetUniformLocation) X(LinkProgram) X(NamedBufferStorage) X(NamedFramebufferTexture) \
    X(ProgramUniform3fv) X(ProgramUniformMatrix3fv) X(ProgramUniformMatrix4fv) X(ReadPixels)            \
    X(ShaderSource) X(TextureStorage2D) X(UseProgram) X(VertexArrayAttribBinding)                       \
    X(VertexArrayAttribFormat) X(VertexArrayElementBuffer) X(VertexArrayVertexBuffer) X(Viewport)
// clang-format on

struct HostGl {
#define HOST_GL_MEMBER(name) decltype(&::gl##name) name = nullptr;
    HOST_GL_FUNCTIONS(HOST_GL_MEMBER)
#undef HOST_GL_MEMBER
};
HostGl gl;

/// Fills `gl`; returns the name of the first entry point the context lacks, empty when none.
std::string loadHostGl() {
#define HOST_GL_LOAD(name)                                                           \
    gl.name = reinterpret_cast<decltype(gl.name)>(OSMesaGetProcAddress("gl" #name)); \
    if (gl.name == nullptr) return "gl" #name;
    HOST_GL_FUNCTIONS(HOST_GL_LOAD)
#undef HOST_GL_LOAD
    return {};
}

constexpr int kWidth = 160;
constexpr int kHeight = 120;
constexpr int kLights = 3;
/// Largest visibility difference allowed between the host's shader and the module's renderer.
constexpr double kTolerance = 1.0 / 255.0;

/// The host's binding points for the module's GLSL: its own units 0-2 and buffer binding 0 stay
/// free for its materials. Written as `#define`s in front of shadow.glsl.
constexpr int kLightBlock = 3, kLayerBlock = 4, kKernelBlock = 5;
constexpr int kCompareUnit = 4, kDepthUnit = 12, kMinMaxUnit = 20;

const char* kVertexShader = R"(#version 450 core
layout(location = 0) in vec3 inPosition;
layout(location = 1) in vec3 inNormal;
uniform mat4 uCsFromLocal;      // object -> camera-relative world (world - camera position)
uniform mat3 uNormalFromLocal;
uniform mat4 uClipFromCs;
out vec3 vCsPosition;
out vec3 vNormal;
void main() {
    vec4 cs = uCsFromLocal * vec4(inPosition, 1.0);
    vCsPosition = cs.xyz;
    vNormal = uNormalFromLocal * inNormal;
    gl_Position = uClipFromCs * cs;
}
)";

/// The host's fragment shader after the module's GLSL: the three lights' visibility.
const char* kFragmentMain = R"(
in vec3 vCsPosition;
in vec3 vNormal;
uniform vec3 uCameraForward;
out vec4 outVisibility;
void main() {
    sg_Surface s = sg_surface(vCsPosition, vNormal);
    float viewDistance = dot(vCsPosition, uCameraForward);
    vec3 v;
    for (int slot = 0; slot < 3; ++slot) v[slot] = sg_lightVisibility(slot, vCsPosition, s, viewDistance);
    outVisibility = vec4(v, 1.0);
}
)";

int fail(const std::string& message) {
    std::fprintf(stderr, "embed_host: %s\n", message.c_str());
    return 1;
}

/// The host's own context: OpenGL 4.5 core through OSMesa, drawing into its own buffer.
struct HostContext {
    OSMesaContext context = nullptr;
    std::vector<unsigned char> colorBuffer = std::vector<unsigned char>(std::size_t{kWidth} * kHeight * 4);

    HostContext() = default;
    HostContext(const HostContext&) = delete;
    HostContext& operator=(const HostContext&) = delete;
    ~HostContext() {
        if (context != nullptr) OSMesaDestroyContext(context);
    }

    /// Creates the context, makes it current and loads the host's GL table; empty or an error.
    std::string create() {
        const int attribs[] = {OSMESA_FORMAT,
                               OSMESA_RGBA,
                               OSMESA_DEPTH_BITS,
                               24,
                               OSMESA_PROFILE,
                               OSMESA_CORE_PROFILE,
                               OSMESA_CONTEXT_MAJOR_VERSION,
                               4,
                               OSMESA_CONTEXT_MINOR_VERSION,
                               5,
                               0};
        context = OSMesaCreateContextAttribs(attribs, nullptr);
        if (context == nullptr) return "OSMesa could not create an OpenGL 4.5 core context";
        if (!OSMesaMakeCurrent(context, colorBuffer.data(), GL_UNSIGNED_BYTE, kWidth, kHeight)) {
            return "OSMesaMakeCurrent failed";
        }
        if (std::string missing = loadHostGl(); !missing.empty()) return "the context lacks " + missing;
        return {};
    }
};

/// The module's part: the scene, its camera, the shadow system and the module's renderer (the
/// reference). Built after `shadow::loadGl`, destroyed while the context is current.
struct Module {
    shadow::Scene scene;
    shadow::CameraView camera;
    /// Made by the factory that returns an error value: this host is built without exceptions.
    std::unique_ptr<shadow::ShadowSystem> shadows;
    shadow::Renderer renderer;

    void buildScene() {
        using namespace shadow;
        addMeshInstance(scene.world, "ground", makePlaneMesh(3.0f, 4), Transform{});
        Transform box;
        box.translation = {0.0, 0.6, 0.0};
        addMeshInstance(scene.world, "box", makeBoxMesh(glm::vec3(0.4f)), box);
        Transform post;
        post.translation = {-1.2, 0.5, 0.8};
        addMeshInstance(scene.world, "post", makeBoxMesh(glm::vec3(0.1f, 0.5f, 0.1f)), post);
        Light spot;
        spot.type = LightType::Spot;
        spot.outerConeAngle = 0.7f;
        spot.radius = 0.15f;
        Shadow pcss;
        pcss.technique = ShadowTechnique::Pcss;
        pcss.mapSize = 256;
        addLight(scene, "spot", spot, pcss, {0.5, 4.0, 0.3}, {0.0, -1.0, 0.0});
        Light bulb;
        bulb.type = LightType::Point;
        bulb.radius = 0.0f;
        Shadow pcf = pcss;
        pcf.technique = ShadowTechnique::Pcf;
        pcf.mapSize = 128;
        addLight(scene, "bulb", bulb, pcf, {-1.0, 2.0, 1.0}, {0.0, -1.0, 0.0});
        Light sun;
        sun.type = LightType::Directional;
        sun.angularRadius = 0.0f;
        Shadow hard = pcss;
        hard.technique = ShadowTechnique::Hard;
        addLight(scene, "sun", sun, hard, {0.0, 10.0, 0.0}, glm::normalize(glm::dvec3(0.3, -1.0, 0.2)));
        const Entity eye = addCamera(scene, "camera", Camera{}, {0.0, 3.0, 5.0}, glm::dvec3(0.0));
        updateTransforms(scene.world);
        camera = makeCameraView(scene.world, eye, static_cast<float>(kWidth) / kHeight);
    }

    /// Step 3: the shadow maps, then the module's own frame with AOVs; the visibility of each
    /// light, rows top first, or an error.
    std::string referenceFrame(std::vector<shadow::ImageF>& visibility, shadow::ImageF& coverage) {
        shadow::FrameStats stats;
        shadow::Result<std::unique_ptr<shadow::ShadowSystem>> made = shadow::ShadowSystem::create();
        if (!made) return made.error().message;
        shadows = std::move(made).value();
        shadows->prepare(scene.world, camera, scene.lights);
        if (const shadow::Status drawn = shadows->tryRender(scene.world, renderer.meshes(), stats); !drawn) {
            return drawn.error().message;
        }
        shadow::RenderOptions options;
        options.width = kWidth;
        options.height = kHeight;
        options.aovs = true;
        renderer.render(scene.world, camera, *shadows, options, stats);
        shadow::FrameImages images = renderer.readback(camera, stats);
        if (images.visibility.size() != kLights) return "the module's frame has no visibility for three lights";
        visibility = std::move(images.visibility);
        coverage = std::move(images.position);
        return {};
    }
};

/// Reads `path`; empty when it cannot.
std::string readFile(const std::string& path) {
    std::ifstream in(path);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
}

/// The host's own include expander, as a game's shader loader has one: `#include "x"` lines of
/// the module's GLSL replaced by x from `dir`, each file once. False (with `error` set) when a
/// file cannot be read.
// NOLINTNEXTLINE(misc-no-recursion): as deep as the module's includes.
bool expandIncludes(const std::string& dir, const std::string& file, std::set<std::string>& seen, std::string& out,
                    std::string& error) {
    if (!seen.insert(file).second) return true;
    const std::string text = readFile(dir + "/" + file);
    if (text.empty()) {
        error = "cannot read " + dir + "/" + file;
        return false;
    }
    static const std::regex kInclude(R"re(^\s*#\s*include\s*"([^"]+)"\s*$)re");
    std::istringstream lines(text);
    std::string line;
    std::smatch m;
    while (std::getline(lines, line)) {
        if (!std::regex_match(line, m, kInclude)) {
            out += line + "\n";
        } else if (!expandIncludes(dir, m[1].str(), seen, out, error)) {
            return false;
        }
    }
    return true;
}

/// One mesh in the host's own buffers.
struct HostMesh {
    GLuint buffer = 0, indices = 0, vertexArray = 0;
    GLsizei count = 0;
    glm::dmat4 worldFromLocal{1.0};
};

/// The host's own pass: its meshes, program and framebuffer (an RGBA32F visibility target).
struct HostPass {
    std::vector<HostMesh> meshes;
    GLuint program = 0, framebuffer = 0, colour = 0, depth = 0;

    HostPass() = default;
    HostPass(const HostPass&) = delete;
    HostPass& operator=(const HostPass&) = delete;
    ~HostPass() {
        for (HostMesh& m : meshes) {
            gl.DeleteVertexArrays(1, &m.vertexArray);
            gl.DeleteBuffers(1, &m.buffer);
            gl.DeleteBuffers(1, &m.indices);
        }
        gl.DeleteProgram(program);
        gl.DeleteFramebuffers(1, &framebuffer);
        gl.DeleteTextures(1, &colour);
        gl.DeleteTextures(1, &depth);
    }

    /// Uploads every mesh of `world`: positions and normals interleaved, and the indices.
    void upload(shadow::World& world) {
        world.view<shadow::Mesh, shadow::WorldTransform>().each([this](shadow::Entity, shadow::Mesh& mesh,
                                                                       shadow::WorldTransform& wt) {
            HostMesh m;
            std::vector<glm::vec3> vertices;
            for (std::size_t i = 0; i < mesh.data->positions.size(); ++i) {
                vertices.push_back(mesh.data->positions[i]);
                vertices.push_back(mesh.data->normals[i]);
            }
            gl.CreateBuffers(1, &m.buffer);
            gl.NamedBufferStorage(m.buffer, static_cast<GLsizeiptr>(vertices.size() * sizeof(glm::vec3)),
                                  vertices.data(), 0);
            gl.CreateBuffers(1, &m.indices);
            gl.NamedBufferStorage(m.indices, static_cast<GLsizeiptr>(mesh.data->indices.size() * sizeof(std::uint32_t)),
                                  mesh.data->indices.data(), 0);
            gl.CreateVertexArrays(1, &m.vertexArray);
            gl.VertexArrayVertexBuffer(m.vertexArray, 0, m.buffer, 0, 2 * sizeof(glm::vec3));
            gl.VertexArrayElementBuffer(m.vertexArray, m.indices);
            for (GLuint a = 0; a < 2; ++a) {
                gl.VertexArrayAttribFormat(m.vertexArray, a, 3, GL_FLOAT, GL_FALSE, a * sizeof(glm::vec3));
                gl.VertexArrayAttribBinding(m.vertexArray, a, 0);
                gl.EnableVertexArrayAttrib(m.vertexArray, a);
            }
            m.count = static_cast<GLsizei>(mesh.data->indices.size());
            m.worldFromLocal = wt.worldFromLocal;
            meshes.push_back(m);
        });
    }

    /// Builds the program: the host's defines, the module's GLSL from `shaderDir`, the host's
    /// main. Empty or an error (a shader log).
    std::string build(const std::string& shaderDir) {
        std::string fragment = "#version 450 core\n";
        for (const auto& [name, value] :
             {std::pair{"SG_BINDING_LIGHTS", kLightBlock}, std::pair{"SG_BINDING_LAYERS", kLayerBlock},
              std::pair{"SG_BINDING_KERNELS", kKernelBlock}, std::pair{"SG_UNIT_SHADOW_COMPARE", kCompareUnit},
              std::pair{"SG_UNIT_SHADOW_DEPTH", kDepthUnit}, std::pair{"SG_UNIT_SHADOW_MINMAX", kMinMaxUnit}}) {
            fragment += std::string("#define ") + name + " " + std::to_string(value) + "\n";
        }
        fragment += "#define SG_TECH_HARD_ENABLED\n#define SG_TECH_PCF_ENABLED\n#define SG_TECH_PCSS_ENABLED\n";
        std::set<std::string> seen;
        if (std::string error; !expandIncludes(shaderDir, "shadow.glsl", seen, fragment, error)) return error;
        fragment += kFragmentMain;
        return link(fragment);
    }

    /// Makes the visibility target: RGBA32F colour and a depth texture.
    void createTarget() {
        gl.CreateTextures(GL_TEXTURE_2D, 1, &colour);
        gl.TextureStorage2D(colour, 1, GL_RGBA32F, kWidth, kHeight);
        gl.CreateTextures(GL_TEXTURE_2D, 1, &depth);
        gl.TextureStorage2D(depth, 1, GL_DEPTH_COMPONENT32F, kWidth, kHeight);
        gl.CreateFramebuffers(1, &framebuffer);
        gl.NamedFramebufferTexture(framebuffer, GL_COLOR_ATTACHMENT0, colour, 0);
        gl.NamedFramebufferTexture(framebuffer, GL_DEPTH_ATTACHMENT, depth, 0);
    }

    /// Step 4: draws every mesh seen by `camera` with the shadow inputs bound. Sets every state
    /// it relies on. Returns the visibility, rows bottom first (GL's order).
    std::vector<glm::vec4> draw(const shadow::CameraView& camera) const {
        const glm::dmat4 viewFromCs = camera.viewFromWorld * glm::translate(glm::dmat4(1.0), camera.wsPosition);
        const glm::dmat4 clipFromView =
            glm::perspective(static_cast<double>(camera.yfov), static_cast<double>(camera.aspect),
                             static_cast<double>(camera.znear), static_cast<double>(camera.zfar));
        const glm::mat4 clipFromCs(clipFromView * viewFromCs);
        const glm::vec3 forward = glm::normalize(glm::vec3(-glm::dvec3(glm::transpose(camera.viewFromWorld)[2])));
        gl.UseProgram(program);
        gl.ProgramUniformMatrix4fv(program, gl.GetUniformLocation(program, "uClipFromCs"), 1, GL_FALSE,
                                   glm::value_ptr(clipFromCs));
        gl.ProgramUniform3fv(program, gl.GetUniformLocation(program, "uCameraForward"), 1, glm::value_ptr(forward));
        gl.BindFramebuffer(GL_FRAMEBUFFER, framebuffer);
        gl.Viewport(0, 0, kWidth, kHeight);
        gl.Enable(GL_DEPTH_TEST);
        gl.DepthFunc(GL_LESS);
        gl.DepthMask(GL_TRUE);
        gl.Disable(GL_CULL_FACE);
        gl.Disable(GL_BLEND);
        gl.ColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
        const float none[4] = {0.0f, 0.0f, 0.0f, 0.0f};
        const float far = 1.0f;
        gl.ClearNamedFramebufferfv(framebuffer, GL_COLOR, 0, none);
        gl.ClearNamedFramebufferfv(framebuffer, GL_DEPTH, 0, &far);
        for (const HostMesh& m : meshes) {
            glm::dmat4 csFromLocal = m.worldFromLocal;
            csFromLocal[3] -= glm::dvec4(camera.wsPosition, 0.0);
            const glm::mat3 normalFromLocal(glm::transpose(glm::inverse(glm::dmat3(m.worldFromLocal))));
            gl.ProgramUniformMatrix4fv(program, gl.GetUniformLocation(program, "uCsFromLocal"), 1, GL_FALSE,
                                       glm::value_ptr(glm::mat4(csFromLocal)));
            gl.ProgramUniformMatrix3fv(program, gl.GetUniformLocation(program, "uNormalFromLocal"), 1, GL_FALSE,
                                       glm::value_ptr(normalFromLocal));
            gl.BindVertexArray(m.vertexArray);
            gl.DrawElements(GL_TRIANGLES, m.count, GL_UNSIGNED_INT, nullptr);
        }
        std::vector<glm::vec4> pixels(std::size_t{kWidth} * kHeight);
        gl.ReadPixels(0, 0, kWidth, kHeight, GL_RGBA, GL_FLOAT, pixels.data());
        return pixels;
    }

private:
    std::string link(const std::string& fragment) {
        const GLuint vs = gl.CreateShader(GL_VERTEX_SHADER);
        gl.ShaderSource(vs, 1, &kVertexShader, nullptr);
        const char* text = fragment.c_str();
        const GLuint fs = gl.CreateShader(GL_FRAGMENT_SHADER);
        gl.ShaderSource(fs, 1, &text, nullptr);
        program = gl.CreateProgram();
        std::string log;
        for (const GLuint s : {vs, fs}) {
            gl.CompileShader(s);
            GLint ok = GL_FALSE;
            gl.GetShaderiv(s, GL_COMPILE_STATUS, &ok);
            if (!ok) {
                std::array<char, 4096> message{};
                gl.GetShaderInfoLog(s, static_cast<GLsizei>(message.size()), nullptr, message.data());
                log += message.data();
            }
            gl.AttachShader(program, s);
        }
        gl.LinkProgram(program);
        GLint linked = GL_FALSE;
        gl.GetProgramiv(program, GL_LINK_STATUS, &linked);
        if (!linked && log.empty()) log = "the host's program did not link";
        gl.DeleteShader(vs);
        gl.DeleteShader(fs);
        return log;
    }
};

/// Step 5 for light `light`: 0 when the host's visibility (rows bottom first) agrees with the
/// module's (rows top first) on every pixel both cover, and the light both shadows and lights.
int compareLight(int light, const std::vector<glm::vec4>& host, const shadow::ImageF& module,
                 const shadow::ImageF& coverage) {
    double worst = 0.0;
    int covered = 0, shadowed = 0, lit = 0;
    for (int y = 0; y < kHeight; ++y) {
        for (int x = 0; x < kWidth; ++x) {
            const glm::vec4& h = host[static_cast<std::size_t>(kHeight - 1 - y) * kWidth + static_cast<std::size_t>(x)];
            if (h.a < 0.5f || coverage.at(x, y, 3) < 0.5f) continue;
            ++covered;
            const float m = module.at(x, y, 0);
            worst = std::max(worst, static_cast<double>(std::abs(h[light] - m)));
            shadowed += m < 0.1f ? 1 : 0;
            lit += m > 0.9f ? 1 : 0;
        }
    }
    std::printf("embed_host: light %d: %d pixels, %d in shadow, %d lit, largest difference %.3g\n", light, covered,
                shadowed, lit, worst);
    if (covered < kWidth * kHeight / 2) return fail("too few pixels covered by both");
    if (shadowed < 100 || lit < 100) return fail("light " + std::to_string(light) + " shows no shadow edge");
    if (worst > kTolerance) return fail("light " + std::to_string(light) + " differs from the module's frame");
    return 0;
}

/// Steps 2-5 (see the file comment), with the context current; 0 when all hold.
int renderAndCheck() {
    Module module;
    module.buildScene();
    std::vector<shadow::ImageF> visibility;
    shadow::ImageF coverage;
    if (std::string error = module.referenceFrame(visibility, coverage); !error.empty()) return fail(error);

    HostPass pass;
    pass.upload(module.scene.world);
    pass.createTarget();
    if (std::string error = pass.build(SHADOW_SHADER_DIR); !error.empty()) return fail(error);
    const std::array<int, kLights> lights{0, 1, 2};
    shadow::ShadowBindingPoints points;
    points.lightBlock = kLightBlock;
    points.layerBlock = kLayerBlock;
    points.kernelBlock = kKernelBlock;
    points.compareUnit = kCompareUnit;
    points.depthUnit = kDepthUnit;
    points.minMaxUnit = kMinMaxUnit;
    const shadow::Result<const shadow::ShadowShaderInputs*> inputs =
        module.shadows->tryShaderInputs(lights, module.camera.wsPosition);
    if (!inputs) return fail(inputs.error().message);
    module.shadows->bindShaderInputs(**inputs, points);
    const std::vector<glm::vec4> host = pass.draw(module.camera);
    if (const GLenum error = gl.GetError(); error != GL_NO_ERROR) return fail("GL error " + std::to_string(error));
    std::printf("embed_host: %s\n", shadow::queryGlInfo().renderer.c_str());
    int status = 0;
    for (int light = 0; light < kLights; ++light) {
        status |= compareLight(light, host, visibility[static_cast<std::size_t>(light)], coverage);
    }
    return status;
}

}  // namespace

int main() {
    HostContext host;
    if (std::string error = host.create(); !error.empty()) return fail(error);
    const shadow::Status loaded =
        shadow::loadGl([](const char* name) { return reinterpret_cast<void*>(OSMesaGetProcAddress(name)); });
    if (!loaded) return fail(loaded.error().message);
    return renderAndCheck();
}
