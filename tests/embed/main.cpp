// A game embedding the shadow engine module, in miniature (README.md, "Embedding"). The host
// owns the OpenGL context, the geometry it draws and its shader; the module owns the scene's
// shadow maps. Step by step, the host
//   1. creates its own OSMesa OpenGL 4.5 core context, loads its own GL table and hands the
//      module the same getProcAddress;
//   2. builds a box over a plane under a spot light with the module's scene API;
//   3. lets the module decide (`prepare`) and draw (`render`) the shadow maps;
//   4. draws the plane with its own vertex buffer, vertex array, sampler and GLSL program, which
//      looks up the light's map (`ShadowSystem::textureOf`) through the matrices of the light's
//      layer plan; the depth it compares is the module's own definition (`lightSpaceDepth`, read
//      from the module's shader directory: the installed copy when it comes as a package);
//   5. reads back the pixel under the box, which must be in shadow, and one beside the box's
//      shadow, which must be lit.
// Exit code 0 when both hold, 1 otherwise (with a message on stderr).
#define GL_GLEXT_PROTOTYPES 1  // declarations only, for the types of the host's GL table below
#include <GL/osmesa.h>

#include <shadow/context.h>
#include <shadow/mesh_cache.h>
#include <shadow/scene.h>
#include <shadow/shadow_system.h>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <array>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace {

// The host's GL table, filled through OSMesaGetProcAddress as a game's loader would (libOSMesa
// does not export the 4.5 entry points as symbols). clang-format would spread the list over
// staircase lines.
// clang-format off
#define HOST_GL_FUNCTIONS(X)                                                                             \
    X(AttachShader) X(BindFramebuffer) X(BindSampler) X(BindTextureUnit) X(BindVertexArray) X(Clear)    \
    X(ClearColor) X(ColorMask) X(CompileShader) X(CreateBuffers) X(CreateProgram) X(CreateSamplers)     \
    X(CreateShader) X(CreateVertexArrays) X(DeleteBuffers) X(DeleteProgram) X(DeleteSamplers)           \
    X(DeleteShader) X(DeleteVertexArrays) X(Disable) X(DrawArrays) X(EnableVertexArrayAttrib)           \
    X(GetError) X(GetProgramiv) X(GetShaderInfoLog) X(GetShaderiv) X(GetUniformLocation)                \
    X(LinkProgram) X(NamedBufferStorage) X(PixelStorei) X(ReadPixels) X(SamplerParameteri)              \
    X(ShaderSource) X(Uniform1f) X(Uniform1i) X(UniformMatrix4fv) X(UseProgram)                         \
    X(VertexArrayAttribBinding) X(VertexArrayAttribFormat) X(VertexArrayVertexBuffer) X(Viewport)
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

constexpr int kWidth = 128;
constexpr int kHeight = 128;
constexpr float kGroundHalfSize = 4.0f;
const glm::dvec3 kBoxCenter{0.0, 1.2, 0.0};
const glm::dvec3 kBoxHalf{0.5, 0.3, 0.5};
const glm::dvec3 kLightPosition{0.0, 4.0, 0.0};
/// Under the box: its shadow on the ground reaches 0.8 m from the centre.
const glm::dvec3 kShadowedPoint{0.0, 0.0, 0.0};
/// Beside the box's shadow, inside the spot's cone (3.4 m wide on the ground).
const glm::dvec3 kLitPoint{2.0, 0.0, 0.5};
/// Depth bias of the host's lookup (m).
constexpr float kBias = 0.02f;

const char* kVertexShader = R"(#version 450 core
layout(location = 0) in vec3 inWsPosition;
uniform mat4 uClipFromWorld;
out vec3 vWsPosition;
void main() {
    vWsPosition = inWsPosition;
    gl_Position = uClipFromWorld * vec4(inWsPosition, 1.0);
}
)";

/// Comes after the module's shadow_common.glsl (which defines `lightSpaceDepth`). One hard
/// comparison: white where the plane is no farther from the light than the map's depth.
const char* kFragmentShader = R"(
in vec3 vWsPosition;
uniform mat4 uLightFromWorld;
uniform mat4 uClipFromLight;
uniform float uDepthScale;
uniform int uOrthographic;
uniform float uBias;
layout(binding = 0) uniform sampler2DArrayShadow uShadowMap;
out vec4 outColor;
void main() {
    vec4 ls = uLightFromWorld * vec4(vWsPosition, 1.0);
    vec4 clip = uClipFromLight * ls;
    vec2 uv = clip.xy / clip.w * 0.5 + 0.5;
    float visibility = 1.0;
    if (clip.w > 0.0 && all(greaterThanEqual(uv, vec2(0.0))) && all(lessThanEqual(uv, vec2(1.0)))) {
        float lsDepth = lightSpaceDepth(ls.xyz, uOrthographic != 0);
        visibility = texture(uShadowMap, vec4(uv, 0.0, (lsDepth - uBias) / uDepthScale));
    }
    outColor = vec4(vec3(visibility), 1.0);
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

/// The module's part: the scene, its camera, the shadow maps and the meshes they are drawn from.
/// Built after `shadow::loadGl`, destroyed while the context is current.
struct ModuleShadows {
    shadow::Scene scene;
    shadow::CameraView camera;
    shadow::ShadowSystem system;
    shadow::MeshCache meshes;

    void buildScene() {
        using namespace shadow;
        addMeshInstance(scene.world, "ground", makePlaneMesh(kGroundHalfSize), Transform{});
        Transform box;
        box.translation = kBoxCenter;
        addMeshInstance(scene.world, "box", makeBoxMesh(glm::vec3(kBoxHalf)), box);
        Light spot;
        spot.type = LightType::Spot;
        spot.outerConeAngle = 0.7f;
        Shadow hard;
        hard.technique = ShadowTechnique::Hard;
        hard.mapSize = 512;
        addLight(scene, "spot", spot, hard, kLightPosition, glm::dvec3(0.0, -1.0, 0.0));
        const Entity eye = addCamera(scene, "camera", Camera{}, glm::dvec3(0.0, 6.0, 6.0), glm::dvec3(0.0));
        updateTransforms(scene.world);
        camera = makeCameraView(scene.world, eye, static_cast<float>(kWidth) / kHeight);
    }

    /// Decides and draws the shadow maps; the light's one layer, or null when it got no map.
    const shadow::ShadowLayerPlan* renderShadowMaps() {
        const shadow::ShadowFrame& frame = system.prepare(scene.world, camera, scene.lights);
        shadow::FrameStats stats;
        system.render(scene.world, meshes, stats);
        if (frame.lights.size() != 1 || !frame.lights[0].hasMap() || system.textureOf(0) == 0) return nullptr;
        return &frame.lights[0].layers[0];
    }

    [[nodiscard]] glm::mat4 clipFromWorld() const {
        return glm::perspective(camera.yfov, camera.aspect, camera.znear, camera.zfar) *
               glm::mat4(camera.viewFromWorld);
    }
};

std::string readFile(const std::string& path) {
    std::ifstream in(path);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
}

/// The host's own pass over the plane: its buffer, vertex array, comparison sampler and program.
struct HostPass {
    GLuint buffer = 0;
    GLuint vertexArray = 0;
    GLuint sampler = 0;
    GLuint program = 0;

    HostPass() = default;
    HostPass(const HostPass&) = delete;
    HostPass& operator=(const HostPass&) = delete;
    ~HostPass() {
        gl.DeleteProgram(program);
        gl.DeleteSamplers(1, &sampler);
        gl.DeleteVertexArrays(1, &vertexArray);
        gl.DeleteBuffers(1, &buffer);
    }

    /// Creates the objects; empty or an error (a shader log).
    std::string create(const std::string& shaderDir) {
        const float h = kGroundHalfSize;
        const std::array<glm::vec3, 4> plane = {glm::vec3(-h, 0, -h), glm::vec3(-h, 0, h), glm::vec3(h, 0, -h),
                                                glm::vec3(h, 0, h)};
        gl.CreateBuffers(1, &buffer);
        gl.NamedBufferStorage(buffer, sizeof(plane), plane.data(), 0);
        gl.CreateVertexArrays(1, &vertexArray);
        gl.VertexArrayVertexBuffer(vertexArray, 0, buffer, 0, sizeof(glm::vec3));
        gl.VertexArrayAttribFormat(vertexArray, 0, 3, GL_FLOAT, GL_FALSE, 0);
        gl.VertexArrayAttribBinding(vertexArray, 0, 0);
        gl.EnableVertexArrayAttrib(vertexArray, 0);
        // The host's own sampler state: the module's texture parameters stay as they are.
        gl.CreateSamplers(1, &sampler);
        gl.SamplerParameteri(sampler, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        gl.SamplerParameteri(sampler, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        gl.SamplerParameteri(sampler, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        gl.SamplerParameteri(sampler, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
        gl.SamplerParameteri(sampler, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
        gl.SamplerParameteri(sampler, GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);

        const std::string common = readFile(shaderDir + "/shadow_common.glsl");
        if (common.find("lightSpaceDepth") == std::string::npos) {
            return "no lightSpaceDepth in " + shaderDir + "/shadow_common.glsl";
        }
        return buildProgram({"#version 450 core\n", common, kFragmentShader});
    }

    /// Draws the plane into the default framebuffer. Sets every state it relies on: the
    /// module's passes leave theirs (viewport, depth test, program, vertex array, ...).
    void draw(const glm::mat4& clipFromWorld, const shadow::ShadowLayerPlan& layer, GLuint shadowMap) const {
        gl.UseProgram(program);
        setMatrix("uClipFromWorld", clipFromWorld);
        setMatrix("uLightFromWorld", glm::mat4(layer.lightFromWorld));
        setMatrix("uClipFromLight", glm::mat4(layer.clipFromLight));
        gl.Uniform1f(gl.GetUniformLocation(program, "uDepthScale"), layer.depthScale);
        gl.Uniform1i(gl.GetUniformLocation(program, "uOrthographic"), layer.orthographic ? 1 : 0);
        gl.Uniform1f(gl.GetUniformLocation(program, "uBias"), kBias);

        gl.BindFramebuffer(GL_FRAMEBUFFER, 0);
        gl.Viewport(0, 0, kWidth, kHeight);
        gl.Disable(GL_DEPTH_TEST);
        gl.Disable(GL_CULL_FACE);
        gl.Disable(GL_BLEND);
        gl.ColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
        gl.ClearColor(0.5f, 0.5f, 0.5f, 1.0f);
        gl.Clear(GL_COLOR_BUFFER_BIT);
        gl.BindTextureUnit(0, shadowMap);
        gl.BindSampler(0, sampler);
        gl.BindVertexArray(vertexArray);
        gl.DrawArrays(GL_TRIANGLE_STRIP, 0, 4);
    }

private:
    std::string buildProgram(const std::vector<std::string>& fragmentParts) {
        const GLuint vs = gl.CreateShader(GL_VERTEX_SHADER);
        gl.ShaderSource(vs, 1, &kVertexShader, nullptr);
        std::vector<const char*> parts;
        for (const std::string& p : fragmentParts) parts.push_back(p.c_str());
        const GLuint fs = gl.CreateShader(GL_FRAGMENT_SHADER);
        gl.ShaderSource(fs, static_cast<GLsizei>(parts.size()), parts.data(), nullptr);
        program = gl.CreateProgram();
        std::string log;
        for (const GLuint s : {vs, fs}) {
            gl.CompileShader(s);
            GLint ok = GL_FALSE;
            gl.GetShaderiv(s, GL_COMPILE_STATUS, &ok);
            if (!ok) {
                std::array<char, 4096> text{};
                gl.GetShaderInfoLog(s, static_cast<GLsizei>(text.size()), nullptr, text.data());
                log += text.data();
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

    void setMatrix(const char* name, const glm::mat4& m) const {
        gl.UniformMatrix4fv(gl.GetUniformLocation(program, name), 1, GL_FALSE, glm::value_ptr(m));
    }
};

/// Red channel of the default framebuffer where `wsPoint` lands (0 = shadow, 255 = lit).
int redAt(const std::vector<unsigned char>& pixels, const glm::mat4& clipFromWorld, const glm::dvec3& wsPoint) {
    const glm::vec4 clip = clipFromWorld * glm::vec4(glm::vec3(wsPoint), 1.0f);
    const glm::vec2 ndc = glm::vec2(clip) / clip.w;
    const glm::ivec2 px = glm::clamp(glm::ivec2((ndc * 0.5f + 0.5f) * glm::vec2(kWidth, kHeight)), glm::ivec2(0),
                                     glm::ivec2(kWidth - 1, kHeight - 1));
    return pixels[(static_cast<std::size_t>(px.y) * kWidth + static_cast<std::size_t>(px.x)) * 4];
}

/// Steps 2-5 (see the file comment), with the context current; 0 when the shadow is right.
int renderAndCheck() {
    ModuleShadows shadows;
    shadows.buildScene();
    const shadow::ShadowLayerPlan* layer = shadows.renderShadowMaps();
    if (layer == nullptr) return fail("the module drew no shadow map for the spot light");

    HostPass pass;
    if (std::string error = pass.create(SHADOW_SHADER_DIR); !error.empty()) return fail(error);
    const glm::mat4 clipFromWorld = shadows.clipFromWorld();
    pass.draw(clipFromWorld, *layer, shadows.system.textureOf(0));

    std::vector<unsigned char> pixels(std::size_t{kWidth} * kHeight * 4);
    gl.PixelStorei(GL_PACK_ALIGNMENT, 1);
    gl.ReadPixels(0, 0, kWidth, kHeight, GL_RGBA, GL_UNSIGNED_BYTE, pixels.data());
    if (const GLenum error = gl.GetError(); error != GL_NO_ERROR) return fail("GL error " + std::to_string(error));
    const int shadowed = redAt(pixels, clipFromWorld, kShadowedPoint);
    const int lit = redAt(pixels, clipFromWorld, kLitPoint);
    std::printf("embed_host: %s; under the box %d, beside its shadow %d (0 = shadow, 255 = lit)\n",
                shadow::queryGlInfo().renderer.c_str(), shadowed, lit);
    int status = 0;
    if (shadowed != 0) status = fail("the point under the box is not in shadow");
    if (lit != 255) status = fail("the point beside the box's shadow is not lit");
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
