// Fragment-shader cost probes: what each piece of the lit pass costs on this renderer.
//
// The lit pass is far slower on llvmpipe than its arithmetic suggests, and the layout choices
// of the frame (render targets, light records, sampler arrays, branches, pre-pass, screen masks)
// should follow measurements. Each probe is one small synthetic fragment shader drawn over a
// full-screen triangle at 1280x720 into a framebuffer object (or, for the overdraw probes, the
// meshes of a real scene; the compute probes of group 13 store a screen-sized image from a
// compute shader instead); its row in the table is the wall-clock time of one frame between
// glFinish fences. Timer queries do not cover rasterisation on a CPU rasteriser (see BENCHMARKS.md),
// so only the wall clock is used. Every probe gets warm-up frames first (the first one includes
// the JIT compile of the shader variant, reported separately), then the timed frames are taken
// round by round over all probes, so that background load on the shared cores spreads over all
// rows alike instead of landing on a few.
//
// The probes read as a list in `listProbes`, grouped and numbered like the questions they
// answer. Each row names its baseline; the table's delta is median minus the baseline's median.
//
//   fragment_costs [--frames N] [--scene SPEC] [--out FILE.md]

#include <shadow/context_osmesa.h>
#include <shadow/mesh_cache.h>
#include <shadow/scene.h>
#include <shadow/gpu_records.h>

#include "gl/gl_api.h"
#include "gl/objects.h"
#include "gl/program.h"

#include "command_line.h"

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <functional>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

namespace shadow {
namespace {

constexpr int kWidth = 1280;
constexpr int kHeight = 720;
constexpr double kMegapixels = kWidth * kHeight / 1e6;
constexpr int kWarmupFrames = 2;
constexpr int kShadowMapSize = 2048;
// Texture units: the comparison map on 0..7 (one sampler, or the elements of a sampler array),
// the screen-space masks after them.
constexpr int kShadowUnit = 0;
constexpr int kSamplerArraySize = 8;
constexpr int kMaskR8Unit = 8;
constexpr int kMaskR16fUnit = 9;

// ---- GLSL of the probes ------------------------------------------------------------------------
// Every fragment shader is prefixed with the engine's shadow_types.glsl (shared constants and the
// sg_GpuLight struct) and the probe's defines.

// A triangle covering the viewport; vUv is [0,1) over the visible pixels.
constexpr const char* kFullScreenVs = R"(#version 450 core
out vec2 vUv;
void main() {
    vec2 p = vec2((gl_VertexID << 1) & 2, gl_VertexID & 2);
    vUv = p;
    gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);
}
)";

// Scene meshes. gl_Position is invariant so that the pre-pass and the EQUAL pass, two programs,
// produce bit-identical depths. vUv is a planar projection so that the tap shaders run unchanged.
constexpr const char* kSceneVs = R"(#version 450 core
layout(location = 0) in vec3 aPosition;
uniform mat4 uClipFromLocal;
uniform mat4 uWorldFromLocal;
out vec2 vUv;
invariant gl_Position;
void main() {
    vec3 wsPosition = (uWorldFromLocal * vec4(aPosition, 1.0)).xyz;
    vUv = wsPosition.xz * 0.1 + 0.5;
    gl_Position = uClipFromLocal * vec4(aPosition, 1.0);
}
)";

constexpr const char* kIo = R"(
in vec2 vUv;
layout(location = 0) out vec4 oColor;
)";

constexpr const char* kConstantFs = R"(
void main() { oColor = vec4(0.25, 0.5, 0.75, 1.0); }
)";

// The engine's AOV layout: colour, position, depth, two visibility targets.
constexpr const char* kConstantAovFs = R"(
layout(location = SG_OUT_COLOR) out vec4 oColor;
layout(location = SG_OUT_POSITION) out vec4 oPosition;
layout(location = SG_OUT_DEPTH) out float oDepth;
layout(location = SG_OUT_VISIBILITY0) out vec4 oVisibility0;
layout(location = SG_OUT_VISIBILITY1) out vec4 oVisibility1;
void main() {
    oColor = vec4(0.25, 0.5, 0.75, 1.0);
    oPosition = vec4(1.0, 2.0, 3.0, 1.0);
    oDepth = 4.0;
    oVisibility0 = vec4(1.0);
    oVisibility1 = vec4(1.0);
}
)";

// The baseline of the shader probes: a varying reaches the output, nothing else.
constexpr const char* kVaryingFs = R"(
void main() { oColor = vec4(vUv, 0.0, 1.0); }
)";

constexpr const char* kDerivativesFs = R"(
void main() {
    float f = vUv.x * vUv.y;
    oColor = vec4(dFdx(f) * 1280.0, dFdy(f) * 720.0, vUv);
}
)";

// A ground plane seen from above, so that every light term varies per pixel, and one spot light
// shaded Blinn-Phong with the range window and the cone of the engine's lighting.
constexpr const char* kSpotLighting = R"(
vec3 csReceiver() { return vec3((vUv.x - 0.5) * 8.0, -1.5, -2.0 - vUv.y * 6.0); }
vec3 csNormal() { return normalize(vec3(0.05 * (vUv.x - 0.5), 1.0, 0.05 * (vUv.y - 0.5))); }

vec3 spotBlinnPhong(vec3 csPosition, vec3 n, vec3 csLight, vec3 direction, vec3 radiance, float range,
                    float cosOuter, float cosInner) {
    vec3 toLight = csLight - csPosition;
    float distance2 = dot(toLight, toLight);
    vec3 l = toLight * inversesqrt(distance2);
    float cone = smoothstep(cosOuter, cosInner, dot(-l, direction));
    float ratio = distance2 / (range * range);
    float window = range > 0.0 ? clamp(1.0 - ratio * ratio, 0.0, 1.0) : 1.0;
    vec3 h = normalize(l + normalize(-csPosition));
    float specular = pow(max(dot(n, h), 0.0), 32.0);
    return radiance * (cone * window * max(dot(n, l), 0.0) / max(distance2, 1e-4)) *
           (vec3(0.8) + vec3(0.04) * specular);
}
vec3 shade(sg_GpuLight L) {
    return spotBlinnPhong(csReceiver(), csNormal(), L.csPosition, L.wsDirection, L.radiance, L.range,
                          L.cosOuter, L.cosInner);
}
)";

constexpr const char* kLightFromUniformsFs = R"(
uniform vec3 uLightPosition;
uniform vec3 uLightDirection;
uniform vec3 uRadiance;
uniform float uRange;
uniform float uCosOuter;
uniform float uCosInner;
void main() {
    oColor = vec4(spotBlinnPhong(csReceiver(), csNormal(), uLightPosition, uLightDirection, uRadiance, uRange,
                                 uCosOuter, uCosInner), 1.0);
}
)";

// LIGHT(i) names where slot i's record comes from; LIGHTS_UBO picks the block. LIGHT_LOOP, when
// defined, is the loop head over the slots; without it one light is shaded in straight code.
constexpr const char* kLightRecordsFs = R"(
#ifdef LIGHTS_UBO
layout(std140, binding = SG_BINDING_LIGHTS) uniform LightBlock { sg_GpuLight uSlots[SG_MAX_LIGHTS_PER_PASS]; };
#else
layout(std430, binding = SG_BINDING_LIGHTS) readonly buffer LightBuffer { sg_GpuLight uLights[]; };
#endif
uniform int uLightCount;
uniform int uFirstLight;
void main() {
    vec3 color = vec3(0.0);
#ifdef LIGHT_LOOP
    LIGHT_LOOP color += shade(LIGHT(i));
#else
    color = shade(LIGHT(0));
#endif
    oColor = vec4(color, 1.0);
}
)";

constexpr const char* kLocalArrayFs = R"(
void main() {
    float a[8];
    int k = int(vUv.x * 8.0) & 7;
    for (int i = 0; i < 8; ++i) a[(i + k) & 7] = vUv.y * float(i);
    int j = int(vUv.y * 8.0) & 7;
    oColor = vec4(a[j] + a[(j + 3) & 7] + a[(j + 5) & 7], vUv, 1.0);
}
)";

// TAP_COUNT hardware-compare taps (each a 2x2 bilinear PCF in the sampler) on a 4-wide grid
// around vUv. TAP_ARRAY, when defined, is the index into an array of samplers; TAP_GUARD, when
// defined, is the condition the block runs under.
constexpr const char* kCompareTapsFs = R"(
#ifdef TAP_ARRAY
layout(binding = SHADOW_UNIT) uniform sampler2DArrayShadow uShadowMaps[SAMPLER_ARRAY_SIZE];
#define TAP_MAP uShadowMaps[TAP_ARRAY]
#else
layout(binding = SHADOW_UNIT) uniform sampler2DArrayShadow uShadowMap;
#define TAP_MAP uShadowMap
#endif
uniform int uZero;
uniform int uSlot;

float compareTaps(int count, vec2 uv, float reference) {
    float sum = 0.0;
    for (int i = 0; i < count; ++i) {
        vec2 offset = vec2(float(i & 3) - 1.5, float(i >> 2) - 1.5) * (2.0 / float(SHADOW_MAP_SIZE));
        sum += texture(TAP_MAP, vec4(uv + offset, 0.0, reference));
    }
    return sum / float(max(count, 1));
}
void main() {
    float visibility = 1.0;
#ifdef TAP_GUARD
    if (TAP_GUARD)
#endif
        visibility = compareTaps(TAP_COUNT, vUv, vUv.y);
    oColor = vec4(visibility, vUv, 1.0);
}
)";

constexpr const char* kMaskFetchFs = R"(
layout(binding = MASK_UNIT) uniform sampler2D uMask;
void main() { oColor = vec4(texelFetch(uMask, ivec2(gl_FragCoord.xy), 0).r, vUv, 1.0); }
)";

// Compute probes: one invocation per column walks its column, as the summed-area table's
// passes do (shadow_summed_area.comp.glsl), storing every texel of a screen-sized image once
// (IMAGE_FORMAT, STORED the stored value), or loading each first (LOAD_FIRST: the table's
// column pass, in place).
constexpr const char* kColumnStoresCs = R"(
layout(local_size_x = 64) in;
layout(binding = 0, IMAGE_FORMAT) uniform IMAGE_TYPE uImage;
void main() {
    int x = int(gl_GlobalInvocationID.x);
    ivec2 size = imageSize(uImage);
    if (x >= size.x) return;
    STORED_TYPE sum = STORED_TYPE(0);
    for (int y = 0; y < size.y; ++y) {
#ifdef LOAD_FIRST
        sum = imageLoad(uImage, ivec2(x, y)) + STORED_TYPE(1);
#else
        sum += STORED_TYPE(1);
#endif
        imageStore(uImage, ivec2(x, y), sum);
    }
}
)";

constexpr const char* kDepthOnlyFs = R"(
void main() {}
)";

// ---- GL helpers --------------------------------------------------------------------------------

/// Links `vertex` with the fragment `parts` below the engine's shadow_types.glsl and `defines`.
gpu::Program buildProbe(const std::string& label, const char* vertex, const std::vector<const char*>& parts,
                        const std::vector<std::string>& defines) {
    gpu::ExpandedSource fragment = gpu::expandShader("shadow_types.glsl", defines);
    // The probe's own lines get a file number of their own, so compiler messages name the probe.
    fragment.text += "#line 1 " + std::to_string(fragment.files.size()) + "\n";
    fragment.files.push_back(label);
    for (const char* part : parts) fragment.text += part;

    return gpu::linkProgram("FragmentCosts/" + label, gpu::ExpandedSource{vertex, {label + " (vertex)"}}, fragment);
}

/// Colour attachments of `colorFormats` (and a depth buffer unless GL_NONE), all draw buffers on.
struct Target {
    std::vector<gpu::Texture> colors;
    gpu::Texture depth;
    gpu::Framebuffer fbo;
};

Target makeTarget(const std::string& label, const std::vector<GLenum>& colorFormats, GLenum depthFormat = GL_NONE) {
    Target t;
    t.fbo = gpu::makeFramebuffer("FragmentCosts/" + label);
    std::vector<GLenum> drawBuffers;
    for (GLenum format : colorFormats) {
        const auto i = static_cast<GLenum>(t.colors.size());
        gpu::Texture& texture = t.colors.emplace_back(
            gpu::makeTexture("FragmentCosts/" + label + "/color" + std::to_string(i), GL_TEXTURE_2D));
        gl.TextureStorage2D(texture.get(), 1, format, kWidth, kHeight);
        gl.NamedFramebufferTexture(t.fbo.get(), GL_COLOR_ATTACHMENT0 + i, texture.get(), 0);
        drawBuffers.push_back(GL_COLOR_ATTACHMENT0 + i);
    }
    gl.NamedFramebufferDrawBuffers(t.fbo.get(), static_cast<GLsizei>(drawBuffers.size()), drawBuffers.data());
    if (depthFormat != GL_NONE) {
        t.depth = gpu::makeTexture("FragmentCosts/" + label + "/depth", GL_TEXTURE_2D);
        gl.TextureStorage2D(t.depth.get(), 1, depthFormat, kWidth, kHeight);
        gl.NamedFramebufferTexture(t.fbo.get(), GL_DEPTH_ATTACHMENT, t.depth.get(), 0);
    }
    if (gl.CheckNamedFramebufferStatus(t.fbo.get(), GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
        throw GlError("FragmentCosts/" + label + ": incomplete framebuffer");
    }
    return t;
}

void clearTarget(const Target& t) {
    const float zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    for (std::size_t i = 0; i < t.colors.size(); ++i) {
        gl.ClearNamedFramebufferfv(t.fbo.get(), GL_COLOR, static_cast<GLint>(i), zero);
    }
    const float far = 1.0f;
    if (t.depth) gl.ClearNamedFramebufferfv(t.fbo.get(), GL_DEPTH, 0, &far);
}

/// A texture of `format` at screen size, filled with `value` (the screen-space masks).
gpu::Texture makeMask(const std::string& label, GLenum format, float value) {
    gpu::Texture t = gpu::makeTexture("FragmentCosts/" + label, GL_TEXTURE_2D);
    gl.TextureStorage2D(t.get(), 1, format, kWidth, kHeight);
    gl.ClearTexSubImage(t.get(), 0, 0, 0, 0, kWidth, kHeight, 1, GL_RED, GL_FLOAT, &value);
    return t;
}

/// One spot light over the probes' ground plane, as the engine packs it; the uniform-fed probe
/// gets the same values.
gpu::GpuLight probeLight() {
    gpu::GpuLight l{};
    l.csPosition = glm::vec3(0.0f, 2.0f, -5.0f);
    l.type = SG_LIGHT_SPOT;
    l.wsDirection = glm::normalize(glm::vec3(0.0f, -1.0f, -0.2f));
    l.range = 20.0f;
    l.radiance = glm::vec3(30.0f);
    l.cosOuter = std::cos(0.7f);
    l.cosInner = std::cos(0.5f);
    return l;
}

/// Sets the uniforms the probes share, on every program that has them.
void setProbeUniforms(GLuint program) {
    const auto loc = [program](const char* name) { return gl.GetUniformLocation(program, name); };
    const gpu::GpuLight l = probeLight();
    gl.ProgramUniform1i(program, loc("uZero"), 0);
    gl.ProgramUniform1i(program, loc("uSlot"), 3);
    gl.ProgramUniform1i(program, loc("uLightCount"), 1);
    gl.ProgramUniform1i(program, loc("uFirstLight"), 0);
    gl.ProgramUniform3fv(program, loc("uLightPosition"), 1, glm::value_ptr(l.csPosition));
    gl.ProgramUniform3fv(program, loc("uLightDirection"), 1, glm::value_ptr(l.wsDirection));
    gl.ProgramUniform3fv(program, loc("uRadiance"), 1, glm::value_ptr(l.radiance));
    gl.ProgramUniform1f(program, loc("uRange"), l.range);
    gl.ProgramUniform1f(program, loc("uCosOuter"), l.cosOuter);
    gl.ProgramUniform1f(program, loc("uCosInner"), l.cosInner);
}

// ---- Probes and their timing -------------------------------------------------------------------

/// One row of the table.
struct Probe {
    Probe(std::string n, std::string b, std::function<void()> f)
        : name(std::move(n)), baseline(std::move(b)), frame(std::move(f)) {}

    std::string name;
    std::string baseline;         ///< row the delta is taken against; empty for none
    std::function<void()> frame;  ///< draws one timed frame
    double firstFrameMs = 0.0;    ///< first warm-up frame: includes the JIT of the variant
    std::vector<double> ms;       ///< timed frames
    glm::vec4 pixelLow{0.0f};     ///< colour at (640, 100) after warm-up (full-screen probes)
    glm::vec4 pixelHigh{0.0f};    ///< colour at (640, 620)
};

double timeFrame(const std::function<void()>& frame) {
    gl.Finish();
    const auto start = std::chrono::steady_clock::now();
    frame();
    gl.Finish();
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

struct Spread {
    double median = 0.0, min = 0.0, max = 0.0;
};

Spread spread(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    const std::size_t n = v.size();
    return {n % 2 == 1 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]), v.front(), v.back()};
}

/// A scene draw: one mesh instance with its matrices.
struct SceneDraw {
    std::shared_ptr<const MeshData> mesh;
    glm::mat4 clipFromLocal;
    glm::mat4 worldFromLocal;
};

/// Fragment counts of the overdraw probes (GL_SAMPLES_PASSED).
struct SceneCounts {
    std::size_t triangles = 0;     ///< submitted per draw of the whole scene
    std::uint64_t rasterised = 0;  ///< depth test ALWAYS: every fragment of every triangle
    std::uint64_t shadedLess = 0;  ///< depth LESS in submission order: fragments shaded
    std::uint64_t visible = 0;     ///< EQUAL after the pre-pass: one per covered pixel
};

/// Everything the probes draw with, made once.
class FragmentCosts {
public:
    explicit FragmentCosts(Scene& scene, const std::string& sceneName);
    /// The probes, in table order.
    std::vector<Probe> listProbes();
    /// Counts fragments of the overdraw probes (untimed).
    SceneCounts countSceneFragments();
    /// Throws unless every store-only compute probe left its column's count, y + 1, in texel
    /// (x, y) of the last column and row.
    void checkComputeProbes() const;

private:
    GLuint program(const std::string& label, const char* vertex, const std::vector<const char*>& parts,
                   const std::vector<std::string>& defines = {});
    Probe fullScreen(const std::string& name, const std::string& baseline, const Target& target,
                     const std::vector<const char*>& parts, const std::vector<std::string>& defines = {},
                     bool blend = false);
    Probe compareTaps(const std::string& name, const std::string& baseline, const std::vector<std::string>& defines);
    /// Compute probe: kColumnStoresCs over a screen-sized image of `format` (an RGBA32F or
    /// unsigned-integer format), loading each texel first when `loadFirst`.
    Probe columnStores(const std::string& name, const std::string& baseline, GLenum format, bool loadFirst = false);
    void drawScene(GLuint program);

    std::vector<gpu::Program> programs_;
    gpu::VertexArray emptyVao_;
    Target rgba8_, rgba16f_, rgba32f_, r8_, r16f_, aovs_, sceneTarget_;
    gpu::Texture shadowMap_, maskR8_, maskR16f_;
    /// A compute probe's image, its format, and whether its probe loads each texel first.
    struct Image {
        gpu::Texture texture;
        GLenum format = GL_NONE;
        bool loadFirst = false;
    };
    std::vector<Image> images_;
    gpu::Buffer lightSsbo_, lightUbo_;
    MeshCache meshes_;
    std::vector<SceneDraw> sceneDraws_;
    GLuint sceneShadeProgram_ = 0, sceneDepthProgram_ = 0;
};

FragmentCosts::FragmentCosts(Scene& scene, const std::string& sceneName)
    : rgba8_(makeTarget("RGBA8", {GL_RGBA8})),
      rgba16f_(makeTarget("RGBA16F", {GL_RGBA16F})),
      rgba32f_(makeTarget("RGBA32F", {GL_RGBA32F})),
      r8_(makeTarget("R8", {GL_R8})),
      r16f_(makeTarget("R16F", {GL_R16F})),
      aovs_(makeTarget("AOVs", {GL_RGBA32F, GL_RGBA32F, GL_R32F, GL_RGBA32F, GL_RGBA32F})),
      sceneTarget_(makeTarget("Scene", {GL_RGBA16F}, GL_DEPTH_COMPONENT32F)) {
    GLuint vao = 0;
    gl.CreateVertexArrays(1, &vao);  // the full-screen triangle comes from gl_VertexID alone
    emptyVao_ = gpu::VertexArray(vao);

    // One layer of a spot light's map, as the shadow system allocates it; a constant depth of
    // 0.5 lets the references vUv.y in [0,1) fall on both sides, which the checks rely on.
    shadowMap_ = gpu::makeTexture("FragmentCosts/shadowMap", GL_TEXTURE_2D_ARRAY);
    gl.TextureStorage3D(shadowMap_.get(), 1, GL_DEPTH_COMPONENT32F, kShadowMapSize, kShadowMapSize, 1);
    gl.TextureParameteri(shadowMap_.get(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    gl.TextureParameteri(shadowMap_.get(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    gl.TextureParameteri(shadowMap_.get(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    gl.TextureParameteri(shadowMap_.get(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    gl.TextureParameteri(shadowMap_.get(), GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
    gl.TextureParameteri(shadowMap_.get(), GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
    const float half = 0.5f;
    gl.ClearTexSubImage(shadowMap_.get(), 0, 0, 0, 0, kShadowMapSize, kShadowMapSize, 1, GL_DEPTH_COMPONENT, GL_FLOAT,
                        &half);
    // The sampler-array probes see the same map in every element: only the indexing differs.
    for (int i = 0; i < kSamplerArraySize; ++i) gl.BindTextureUnit(kShadowUnit + i, shadowMap_.get());

    maskR8_ = makeMask("maskR8", GL_R8, 0.75f);
    maskR16f_ = makeMask("maskR16F", GL_R16F, 0.75f);
    gl.BindTextureUnit(kMaskR8Unit, maskR8_.get());
    gl.BindTextureUnit(kMaskR16fUnit, maskR16f_.get());

    // GpuLight has one layout under std430 and std140 (every vec3 is followed by a scalar and
    // the size is a multiple of 16), so one array feeds both blocks.
    const std::vector<gpu::GpuLight> lights(SG_MAX_LIGHTS_PER_PASS, probeLight());
    const auto bytes = static_cast<GLsizeiptr>(lights.size() * sizeof(gpu::GpuLight));
    lightSsbo_ = gpu::makeBuffer("FragmentCosts/lightsSsbo", bytes, lights.data(), 0);
    lightUbo_ = gpu::makeBuffer("FragmentCosts/lightsUbo", bytes, lights.data(), 0);
    gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, SG_BINDING_LIGHTS, lightSsbo_.get());
    gl.BindBufferBase(GL_UNIFORM_BUFFER, SG_BINDING_LIGHTS, lightUbo_.get());

    animate(scene.world, 0.0);
    (void)updateTransforms(scene.world);
    const Entity camera = scene.cameras.empty() ? addDefaultCamera(scene) : scene.cameras.front();
    const CameraView view = makeCameraView(scene.world, camera, static_cast<float>(kWidth) / kHeight);
    const glm::dmat4 clipFromWorld = glm::perspective(static_cast<double>(view.yfov), static_cast<double>(view.aspect),
                                                      static_cast<double>(view.znear), static_cast<double>(view.zfar)) *
                                     view.viewFromWorld;
    scene.world.view<Mesh, WorldTransform>().each([&](Entity, Mesh& mesh, WorldTransform& wt) {
        if (mesh.data && wt.finite) {
            sceneDraws_.push_back(
                {mesh.data, glm::mat4(clipFromWorld * wt.worldFromLocal), glm::mat4(wt.worldFromLocal)});
        }
    });
    sceneShadeProgram_ = program(sceneName + "/16 taps", kSceneVs, {kIo, kCompareTapsFs}, {"TAP_COUNT 16"});
    sceneDepthProgram_ = program(sceneName + "/depth only", kSceneVs, {kDepthOnlyFs});
    gl.Viewport(0, 0, kWidth, kHeight);
}

GLuint FragmentCosts::program(const std::string& label, const char* vertex, const std::vector<const char*>& parts,
                              const std::vector<std::string>& defines) {
    std::vector<std::string> all = {"SHADOW_UNIT " + std::to_string(kShadowUnit),
                                    "SAMPLER_ARRAY_SIZE " + std::to_string(kSamplerArraySize),
                                    "SHADOW_MAP_SIZE " + std::to_string(kShadowMapSize)};
    all.insert(all.end(), defines.begin(), defines.end());
    const GLuint p = programs_.emplace_back(buildProbe(label, vertex, parts, all)).get();
    setProbeUniforms(p);
    return p;
}

Probe FragmentCosts::fullScreen(const std::string& name, const std::string& baseline, const Target& target,
                                const std::vector<const char*>& parts, const std::vector<std::string>& defines,
                                bool blend) {
    const GLuint p = program(name, kFullScreenVs, parts, defines);
    const GLuint fbo = target.fbo.get();
    const GLuint vao = emptyVao_.get();
    return {name, baseline, [p, fbo, vao, blend] {
                gl.BindFramebuffer(GL_FRAMEBUFFER, fbo);
                gl.UseProgram(p);
                gl.BindVertexArray(vao);
                if (blend) {
                    gl.Enable(GL_BLEND);
                    gl.BlendFunc(GL_ONE, GL_ONE);
                }
                gl.DrawArrays(GL_TRIANGLES, 0, 3);
                gl.Disable(GL_BLEND);
            }};
}

Probe FragmentCosts::compareTaps(const std::string& name, const std::string& baseline,
                                 const std::vector<std::string>& defines) {
    return fullScreen(name, baseline, rgba16f_, {kIo, kCompareTapsFs}, defines);
}

Probe FragmentCosts::columnStores(const std::string& name, const std::string& baseline, GLenum format, bool loadFirst) {
    struct Format {
        GLenum format;
        const char* layout;
        const char* stored;
    };
    static constexpr std::array<Format, 4> kFormats{{{GL_RGBA32F, "rgba32f", "vec4"},
                                                     {GL_RGBA32UI, "rgba32ui", "uvec4"},
                                                     {GL_RG32UI, "rg32ui", "uvec4"},
                                                     {GL_R32UI, "r32ui", "uvec4"}}};
    const auto* f =
        std::find_if(kFormats.begin(), kFormats.end(), [format](const Format& k) { return k.format == format; });
    if (f == kFormats.end()) throw std::logic_error("columnStores: no probe for this image format");
    const bool floats = format == GL_RGBA32F;
    std::string text = std::string("#version 450 core\n#define IMAGE_FORMAT ") + f->layout + "\n#define IMAGE_TYPE " +
                       (floats ? "image2D" : "uimage2D") + "\n#define STORED_TYPE " + f->stored + "\n" +
                       (loadFirst ? "#define LOAD_FIRST\n" : "") + "#line 1 1\n" + kColumnStoresCs;
    const GLuint p =
        programs_.emplace_back(gpu::linkComputeProgram("FragmentCosts/" + name, {std::move(text), {"defines", name}}))
            .get();
    const Image& image =
        images_.emplace_back(Image{gpu::makeTexture("FragmentCosts/" + name, GL_TEXTURE_2D), format, loadFirst});
    gl.TextureStorage2D(image.texture.get(), 1, format, kWidth, kHeight);
    const GLuint texture = image.texture.get();
    return {name, baseline, [p, texture, format] {
                gl.UseProgram(p);
                gl.BindImageTexture(0, texture, 0, GL_FALSE, 0, GL_READ_WRITE, format);
                gl.DispatchCompute((kWidth + 63) / 64, 1, 1);
                gl.MemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
            }};
}

void FragmentCosts::drawScene(GLuint program) {
    gl.UseProgram(program);
    const GLint clipFromLocal = gl.GetUniformLocation(program, "uClipFromLocal");
    const GLint worldFromLocal = gl.GetUniformLocation(program, "uWorldFromLocal");
    for (const SceneDraw& d : sceneDraws_) {
        const int indexCount = meshes_.bind(d.mesh);  // uploads on the first (warm-up) frame only
        gl.ProgramUniformMatrix4fv(program, clipFromLocal, 1, GL_FALSE, glm::value_ptr(d.clipFromLocal));
        gl.ProgramUniformMatrix4fv(program, worldFromLocal, 1, GL_FALSE, glm::value_ptr(d.worldFromLocal));
        gl.DrawElements(GL_TRIANGLES, indexCount, GL_UNSIGNED_INT, nullptr);
    }
}

std::vector<Probe> FragmentCosts::listProbes() {
    std::vector<Probe> p;
    const std::string constRgba8 = "1. const → RGBA8", constRgba16f = "1. const → RGBA16F";
    const std::string varying = "varying → RGBA16F (shader baseline)";
    const std::string taps16 = "8. 16 compare taps";

    // 1-3. What the render target costs with no shading at all.
    p.push_back(fullScreen(constRgba8, "", rgba8_, {kIo, kConstantFs}));
    p.push_back(fullScreen(constRgba16f, constRgba8, rgba16f_, {kIo, kConstantFs}));
    p.push_back(fullScreen("1. const → RGBA32F", constRgba8, rgba32f_, {kIo, kConstantFs}));
    p.push_back(fullScreen("2. const → 5 MRT AOVs (4×RGBA32F + R32F)", constRgba16f, aovs_, {kConstantAovFs}));
    p.push_back(fullScreen("3. blend ONE,ONE → RGBA16F", constRgba16f, rgba16f_, {kIo, kConstantFs}, {}, true));
    p.push_back(fullScreen("3. blend ONE,ONE → RGBA32F", "1. const → RGBA32F", rgba32f_, {kIo, kConstantFs}, {}, true));

    // 4-7. Shader pieces, all into one RGBA16F target, against a varying passed through.
    p.push_back(fullScreen(varying, constRgba16f, rgba16f_, {kIo, kVaryingFs}));
    p.push_back(fullScreen("4. dFdx/dFdy of a varying", varying, rgba16f_, {kIo, kDerivativesFs}));
    const std::string spotUniforms = "5. spot Blinn-Phong, plain uniforms";
    const std::string spotSsbo = "6. spot from SSBO[0] (GpuLight, std430)";
    const std::string loopSsbo = "6. 8-slot loop, SSBO[uFirst+i], count 1";
    // Eight slots with a runtime test (unrolled by the compiler), or a loop bounded by the count.
    const std::string slotLoop = "LIGHT_LOOP for (int i = 0; i < SG_MAX_LIGHTS_PER_PASS; ++i) if (i < uLightCount)";
    const std::string countLoop = "LIGHT_LOOP for (int i = 0; i < uLightCount; ++i)";
    p.push_back(fullScreen(spotUniforms, varying, rgba16f_, {kIo, kSpotLighting, kLightFromUniformsFs}));
    p.push_back(
        fullScreen(spotSsbo, spotUniforms, rgba16f_, {kIo, kSpotLighting, kLightRecordsFs}, {"LIGHT(i) uLights[i]"}));
    p.push_back(fullScreen("6. spot from UBO[0] (GpuLight, std140)", spotUniforms, rgba16f_,
                           {kIo, kSpotLighting, kLightRecordsFs}, {"LIGHTS_UBO", "LIGHT(i) uSlots[i]"}));
    // The index is 0 everywhere but per-pixel to the compiler, as a cascade or layer index is.
    p.push_back(fullScreen("6. spot from UBO[per-pixel index] (std140)", "6. spot from UBO[0] (GpuLight, std140)",
                           rgba16f_, {kIo, kSpotLighting, kLightRecordsFs},
                           {"LIGHTS_UBO", "LIGHT(i) uSlots[(i) + int(vUv.x * 0.5)]"}));
    p.push_back(fullScreen(loopSsbo, spotSsbo, rgba16f_, {kIo, kSpotLighting, kLightRecordsFs},
                           {slotLoop, "LIGHT(i) uLights[uFirstLight + (i)]"}));
    p.push_back(fullScreen("6. 8-slot loop, UBO[i] unrolled (std140), count 1", loopSsbo, rgba16f_,
                           {kIo, kSpotLighting, kLightRecordsFs}, {"LIGHTS_UBO", slotLoop, "LIGHT(i) uSlots[i]"}));
    p.push_back(fullScreen("6. loop i < uLightCount, SSBO[uFirst+i], count 1", spotSsbo, rgba16f_,
                           {kIo, kSpotLighting, kLightRecordsFs}, {countLoop, "LIGHT(i) uLights[uFirstLight + (i)]"}));
    p.push_back(fullScreen("7. float[8], dynamic index writes + reads", varying, rgba16f_, {kIo, kLocalArrayFs}));

    // 8-9. Hardware-compare taps on one 2048² DEPTH32F layer, then through an array of samplers.
    p.push_back(compareTaps("8. 1 compare tap", varying, {"TAP_COUNT 1"}));
    p.push_back(compareTaps(taps16, varying, {"TAP_COUNT 16"}));
    p.push_back(compareTaps("8. 32 compare taps", varying, {"TAP_COUNT 32"}));
    p.push_back(compareTaps("9. 16 taps, sampler[8] constant index", taps16, {"TAP_COUNT 16", "TAP_ARRAY 3"}));
    p.push_back(compareTaps("9. 16 taps, sampler[8] uniform index", "9. 16 taps, sampler[8] constant index",
                            {"TAP_COUNT 16", "TAP_ARRAY uSlot"}));

    // 10. Early-outs: a block that never runs should cost nothing over the baseline.
    p.push_back(compareTaps("10. 16 taps in if (uniform false)", varying, {"TAP_COUNT 16", "TAP_GUARD uZero != 0"}));
    p.push_back(
        compareTaps("10. 16 taps in if (per-pixel false)", varying, {"TAP_COUNT 16", "TAP_GUARD vUv.x < -1.0"}));
    p.push_back(compareTaps("10. tap loop, per-pixel trip count 0", varying, {"TAP_COUNT int(vUv.x * 0.5)"}));
    p.push_back(compareTaps("10. tap loop, per-pixel trip count 16", taps16, {"TAP_COUNT (16 + int(vUv.x * 0.5))"}));

    // 11. Overdraw on a real scene; every frame clears colour and depth first.
    const Target& st = sceneTarget_;
    const std::string sceneClear = "11. scene: clear colour + depth";
    const std::string sceneLess = "11. scene: 16 taps, depth LESS, submission order";
    const GLuint shadeProgram = sceneShadeProgram_, depthProgram = sceneDepthProgram_;
    const auto depthPrePass = [this, depthProgram] {
        gl.DepthFunc(GL_LESS);
        gl.ColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
        drawScene(depthProgram);
        gl.ColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    };
    p.push_back({sceneClear, "", [&st] {
                     gl.BindFramebuffer(GL_FRAMEBUFFER, st.fbo.get());
                     clearTarget(st);
                 }});
    p.push_back({sceneLess, sceneClear, [this, &st, shadeProgram] {
                     gl.BindFramebuffer(GL_FRAMEBUFFER, st.fbo.get());
                     clearTarget(st);
                     gl.Enable(GL_DEPTH_TEST);
                     gl.DepthFunc(GL_LESS);
                     drawScene(shadeProgram);
                     gl.Disable(GL_DEPTH_TEST);
                 }});
    p.push_back({"11. scene: vertex stage only (rasterizer discard)", "", [this, depthProgram] {
                     gl.Enable(GL_RASTERIZER_DISCARD);
                     drawScene(depthProgram);
                     gl.Disable(GL_RASTERIZER_DISCARD);
                 }});
    p.push_back({"11. scene: depth-only pre-pass alone", sceneClear, [&st, depthPrePass] {
                     gl.BindFramebuffer(GL_FRAMEBUFFER, st.fbo.get());
                     clearTarget(st);
                     gl.Enable(GL_DEPTH_TEST);
                     depthPrePass();
                     gl.Disable(GL_DEPTH_TEST);
                 }});
    // The engine draws two-sided; culling shows how much of a pass is per-triangle work.
    p.push_back({"11. scene: depth-only pre-pass, back faces culled", "11. scene: depth-only pre-pass alone",
                 [&st, depthPrePass] {
                     gl.BindFramebuffer(GL_FRAMEBUFFER, st.fbo.get());
                     clearTarget(st);
                     gl.Enable(GL_DEPTH_TEST);
                     gl.Enable(GL_CULL_FACE);
                     depthPrePass();
                     gl.Disable(GL_CULL_FACE);
                     gl.Disable(GL_DEPTH_TEST);
                 }});
    p.push_back(
        {"11. scene: pre-pass + 16 taps EQUAL, no depth writes", sceneLess, [this, &st, depthPrePass, shadeProgram] {
             gl.BindFramebuffer(GL_FRAMEBUFFER, st.fbo.get());
             clearTarget(st);
             gl.Enable(GL_DEPTH_TEST);
             depthPrePass();
             gl.DepthFunc(GL_EQUAL);
             gl.DepthMask(GL_FALSE);
             drawScene(shadeProgram);
             gl.DepthMask(GL_TRUE);
             gl.Disable(GL_DEPTH_TEST);
         }});

    // 12. Screen-space masks: reading one, writing one, and the pass break a mask pass costs.
    p.push_back(fullScreen("12. texelFetch R8 screen mask", varying, rgba16f_, {kIo, kMaskFetchFs},
                           {"MASK_UNIT " + std::to_string(kMaskR8Unit)}));
    p.push_back(fullScreen("12. texelFetch R16F screen mask", varying, rgba16f_, {kIo, kMaskFetchFs},
                           {"MASK_UNIT " + std::to_string(kMaskR16fUnit)}));
    p.push_back(fullScreen("12. const → R8", constRgba8, r8_, {kIo, kConstantFs}));
    p.push_back(fullScreen("12. const → R16F", constRgba16f, r16f_, {kIo, kConstantFs}));
    // Blended, so that the second draw cannot make the rasteriser drop the first (an opaque
    // full-screen draw replaces what is binned before it).
    Probe once = fullScreen("12. 2 × blend → RGBA16F, one FBO", "", rgba16f_, {kIo, kConstantFs}, {}, true);
    const std::function<void()> draw = once.frame;
    once.frame = [draw] {
        draw();
        draw();
    };
    const std::string twoDraws = once.name;
    p.push_back(std::move(once));
    const GLuint maskFbo = r8_.fbo.get();
    const Target& r8 = r8_;
    p.push_back({"12. same + bind and clear an R8 FBO between", twoDraws, [draw, maskFbo, &r8] {
                     draw();
                     gl.BindFramebuffer(GL_FRAMEBUFFER, maskFbo);
                     clearTarget(r8);
                     draw();  // binds the RGBA16F target again
                 }});
    p.push_back({"12. bind and clear an R8 FBO alone", "", [maskFbo, &r8] {
                     gl.BindFramebuffer(GL_FRAMEBUFFER, maskFbo);
                     clearTarget(r8);
                 }});

    // 13. Compute stores: the summed-area table (VSSM) is written by compute passes, one
    // invocation per line, each storing every texel of its line; against the fragment write of
    // the same texels (row 1).
    const std::string storeRgba32f = "13. compute: store each texel, RGBA32F";
    p.push_back(columnStores(storeRgba32f, "1. const → RGBA32F", GL_RGBA32F));
    p.push_back(columnStores("13. compute: store each texel, RGBA32UI", storeRgba32f, GL_RGBA32UI));
    p.push_back(columnStores("13. compute: store each texel, RG32UI", storeRgba32f, GL_RG32UI));
    p.push_back(columnStores("13. compute: store each texel, R32UI", storeRgba32f, GL_R32UI));
    p.push_back(columnStores("13. compute: load + store each texel, RGBA32F", storeRgba32f, GL_RGBA32F, true));
    return p;
}

void FragmentCosts::checkComputeProbes() const {
    gl.MemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT);
    for (std::size_t i = 0; i < images_.size(); ++i) {
        if (images_[i].loadFirst) continue;
        std::array<std::uint32_t, 4> texel{};
        const bool floats = images_[i].format == GL_RGBA32F;
        gl.GetTextureSubImage(images_[i].texture.get(), 0, kWidth - 1, kHeight - 1, 0, 1, 1, 1,
                              floats ? GL_RGBA : GL_RGBA_INTEGER, floats ? GL_FLOAT : GL_UNSIGNED_INT, sizeof(texel),
                              texel.data());
        float first = 0.0f;
        std::memcpy(&first, texel.data(), sizeof(first));
        const double value = floats ? static_cast<double>(first) : static_cast<double>(texel[0]);
        if (value != kHeight) {
            throw std::logic_error("compute probe " + std::to_string(i) + " stored " + std::to_string(value) +
                                   " in its last texel, not " + std::to_string(kHeight));
        }
    }
}

SceneCounts FragmentCosts::countSceneFragments() {
    GLuint query = 0;
    gl.CreateQueries(GL_SAMPLES_PASSED, 1, &query);
    const auto count = [query](const std::function<void()>& draw) {
        gl.BeginQuery(GL_SAMPLES_PASSED, query);
        draw();
        gl.EndQuery(GL_SAMPLES_PASSED);
        std::uint64_t n = 0;
        gl.GetQueryObjectui64v(query, GL_QUERY_RESULT, &n);
        return n;
    };
    SceneCounts c;
    for (const SceneDraw& d : sceneDraws_) c.triangles += d.mesh->indices.size() / 3;
    gl.BindFramebuffer(GL_FRAMEBUFFER, sceneTarget_.fbo.get());
    gl.Enable(GL_DEPTH_TEST);
    clearTarget(sceneTarget_);
    gl.DepthFunc(GL_ALWAYS);
    c.rasterised = count([this] { drawScene(sceneShadeProgram_); });
    clearTarget(sceneTarget_);
    gl.DepthFunc(GL_LESS);
    c.shadedLess = count([this] { drawScene(sceneShadeProgram_); });
    gl.DepthFunc(GL_EQUAL);
    gl.DepthMask(GL_FALSE);
    c.visible = count([this] { drawScene(sceneShadeProgram_); });
    gl.DepthMask(GL_TRUE);
    gl.Disable(GL_DEPTH_TEST);
    gl.DeleteQueries(1, &query);
    return c;
}

/// Warm-up frames for every probe, then timed frames round by round.
void measure(std::vector<Probe>& probes, int frames) {
    for (Probe& p : probes) {
        for (int i = 0; i < kWarmupFrames; ++i) {
            const double ms = timeFrame(p.frame);
            if (i == 0) p.firstFrameMs = ms;
        }
        // The full-screen probes leave their colour in the bound framebuffer's first target.
        gl.Finish();
        GLint fbo = 0;
        gl.GetIntegerv(GL_FRAMEBUFFER_BINDING, &fbo);
        gl.NamedFramebufferReadBuffer(static_cast<GLuint>(fbo), GL_COLOR_ATTACHMENT0);
        gl.ReadPixels(kWidth / 2, 100, 1, 1, GL_RGBA, GL_FLOAT, glm::value_ptr(p.pixelLow));
        gl.ReadPixels(kWidth / 2, kHeight - 100, 1, 1, GL_RGBA, GL_FLOAT, glm::value_ptr(p.pixelHigh));
        gpu::checkGlError("probe '" + p.name + "'");
    }
    for (int round = 0; round < frames; ++round) {
        for (Probe& p : probes) p.ms.push_back(timeFrame(p.frame));
    }
}

/// The probe named `name`, or else the first whose name starts with it.
const Probe& row(const std::vector<Probe>& probes, const std::string& name) {
    for (const Probe& p : probes) {
        if (p.name == name) return p;
    }
    for (const Probe& p : probes) {
        if (p.name.rfind(name, 0) == 0) return p;
    }
    throw std::logic_error("no probe named '" + name + "'");
}

/// Probes that must agree before their times mean anything: the light records read the data
/// the uniforms hold, the taps see both sides of the map, the sampler arrays see the same map.
void checkProbes(const std::vector<Probe>& probes) {
    const auto near = [](const glm::vec4& a, const glm::vec4& b) {
        return glm::all(glm::lessThanEqual(glm::abs(a - b), glm::vec4(1e-3f) + 1e-3f * glm::abs(b)));
    };
    const Probe& uniforms = row(probes, "5. spot Blinn-Phong");
    if (uniforms.pixelHigh.r <= 0.0f && uniforms.pixelLow.r <= 0.0f) {
        throw std::logic_error("the spot light probe is black at both sample pixels");
    }
    for (const char* name : {"6. spot from SSBO", "6. spot from UBO[0]", "6. spot from UBO[per-pixel",
                             "6. 8-slot loop, SSBO", "6. 8-slot loop, UBO", "6. loop i < uLightCount"}) {
        const Probe& p = row(probes, name);
        if (!near(p.pixelLow, uniforms.pixelLow) || !near(p.pixelHigh, uniforms.pixelHigh)) {
            throw std::logic_error("'" + p.name + "' does not shade like the uniform-fed light");
        }
    }
    const Probe& taps = row(probes, "8. 16 compare taps");
    if (std::abs(taps.pixelLow.r - taps.pixelHigh.r) < 0.5f) {
        throw std::logic_error("the compare taps do not see both sides of the map");
    }
    for (const char* name : {"9. 16 taps, sampler[8] constant", "9. 16 taps, sampler[8] uniform"}) {
        const Probe& p = row(probes, name);
        if (!near(p.pixelLow, taps.pixelLow) || !near(p.pixelHigh, taps.pixelHigh)) {
            throw std::logic_error("'" + p.name + "' does not read what the single sampler reads");
        }
    }
}

std::string machineName() {
    std::ifstream cpuinfo("/proc/cpuinfo");
    std::string line;
    while (std::getline(cpuinfo, line)) {
        if (line.rfind("model name", 0) == 0) return line.substr(line.find(':') + 2);
    }
    return "unknown CPU";
}

/// The 1-minute load average: the cores are shared, and a loaded machine stretches every row.
std::string loadAverage() {
    std::ifstream file("/proc/loadavg");
    std::string first;
    return (file >> first) ? first : "unknown";
}

std::string fixed(double v, int digits = 2) {
    std::ostringstream s;
    s << std::fixed << std::setprecision(digits) << v;
    return s.str();
}

std::string markdown(const std::vector<Probe>& probes, const SceneCounts& counts, const std::string& renderer,
                     const std::string& sceneName, int frames, const std::string& loadBefore) {
    const char* threads = std::getenv("LP_NUM_THREADS");
    std::ostringstream md;
    md << "# Fragment-shader costs\n\n"
       << "Renderer `" << renderer << "` on " << machineName() << ", " << std::thread::hardware_concurrency()
       << " CPUs, LP_NUM_THREADS " << (threads != nullptr ? threads : "unset") << ", load average " << loadBefore
       << " before and " << loadAverage() << " after the run. " << kWidth << "x" << kHeight
       << ", wall clock between glFinish fences, " << kWarmupFrames << " warm-up frames, then " << frames
       << " timed frames per probe taken round by round over all probes. Deltas are median minus the named "
          "baseline's median. Full-screen rows write RGBA16F unless the row says otherwise; "
          "ms / MPix divides by the screen's "
       << fixed(kMegapixels, 4) << " MPix (also for the scene rows). The last column is the first warm-up "
       << "frame, which includes the JIT compile of the shader variant (Mesa's shader cache is off for the "
       << "run).\n\n"
       << "Produced by `bash benchmarks/run_fragment_costs.sh` (benchmarks/fragment_costs.cpp).\n\n"
       << "| piece | ms median | min | max | ms / MPix | Δ median vs baseline | 1st frame ms |\n"
       << "|---|---:|---:|---:|---:|---|---:|\n";
    for (const Probe& p : probes) {
        const Spread s = spread(p.ms);
        std::string delta = "—";
        if (!p.baseline.empty()) {
            const double base = spread(row(probes, p.baseline).ms).median;
            // Streamed, not `"literal" + std::string`: GCC 12 reports that as an overlapping copy.
            std::ostringstream d;
            d << (s.median >= base ? "+" : "") << fixed(s.median - base) << " (×" << fixed(s.median / base) << ") vs "
              << p.baseline;
            delta = d.str();
        }
        md << "| " << p.name << " | " << fixed(s.median) << " | " << fixed(s.min) << " | " << fixed(s.max) << " | "
           << fixed(s.median / kMegapixels) << " | " << delta << " | " << fixed(p.firstFrameMs, 1) << " |\n";
    }

    const auto median = [&probes](const std::string& name) { return spread(row(probes, name).ms).median; };
    const double base = median("varying → RGBA16F");
    const double block = median("8. 16 compare taps") - base;
    const auto paid = [&](const std::string& name) { return fixed(100.0 * (median(name) - base) / block, 0) + " %"; };
    const double less = median("11. scene: 16 taps, depth LESS");
    // Shading alone in the scene: the LESS pass minus the depth-only pass (same triangles, same
    // depth work), per shaded fragment, against the full-screen 16-tap pass per pixel.
    const double sceneShadingPerMFrag = (less - median("11. scene: depth-only pre-pass alone")) /
                                        (static_cast<double>(std::max<std::uint64_t>(counts.shadedLess, 1)) / 1e6);
    const double screenShadingPerMPix = median("8. 16 compare taps") / kMegapixels;
    const double prePass = median("11. scene: pre-pass + 16 taps EQUAL");
    const Probe& constantIndex = row(probes, "9. 16 taps, sampler[8] constant index");
    const Probe& uniformIndex = row(probes, "9. 16 taps, sampler[8] uniform index");
    md << "\n## Derived\n\n"
       << "Share of the 16-tap block's cost (" << fixed(block) << " ms over the varying baseline) still paid when "
       << "the block does not run:\n\n"
       << "- `if` on a uniform that is false: " << paid("10. 16 taps in if (uniform false)") << "\n"
       << "- `if` on a per-pixel condition false everywhere: " << paid("10. 16 taps in if (per-pixel false)") << "\n"
       << "- loop whose per-pixel trip count is 0 everywhere: " << paid("10. tap loop, per-pixel trip count 0")
       << "\n\n"
       << "Sampler array: the first frame (JIT) of 16 taps through `sampler[8]` takes "
       << fixed(uniformIndex.firstFrameMs, 0) << " ms with a uniform index against "
       << fixed(constantIndex.firstFrameMs, 0) << " ms with a constant one.\n\n"
       << "Scene `" << sceneName << "` (its own camera; fragments counted with GL_SAMPLES_PASSED):\n\n"
       << "- triangles drawn per pass: " << counts.triangles << "\n"
       << "- fragments rasterised (depth test ALWAYS): " << counts.rasterised << " — depth complexity "
       << fixed(static_cast<double>(counts.rasterised) /
                static_cast<double>(std::max<std::uint64_t>(counts.visible, 1)))
       << "\n"
       << "- fragments shaded with depth LESS in submission order: " << counts.shadedLess << "\n"
       << "- visible fragments (EQUAL after the pre-pass): " << counts.visible << " ("
       << fixed(100.0 * static_cast<double>(counts.visible) / (kWidth * kHeight), 1) << " % of the screen)\n"
       << "- overdraw factor of the shaded pass (LESS / visible): "
       << fixed(static_cast<double>(counts.shadedLess) /
                static_cast<double>(std::max<std::uint64_t>(counts.visible, 1)))
       << "\n"
       << "- shading cost per fragment, scene vs full screen (small triangles shade partly covered 4x4 "
       << "blocks): " << fixed(sceneShadingPerMFrag) << " vs " << fixed(screenShadingPerMPix) << " ms per M (×"
       << fixed(sceneShadingPerMFrag / screenShadingPerMPix) << ")\n"
       << "- pre-pass + EQUAL vs LESS: " << fixed(prePass) << " ms vs " << fixed(less) << " ms ("
       << (prePass <= less ? "saves " : "costs ") << fixed(std::abs(less - prePass)) << " ms)\n";
    const double storeRgba = median("13. compute: store each texel, RGBA32F");
    md << "\nCompute stores (the summed-area table's passes store every texel of the layer; ms / MPix is ns per "
          "texel): one RGBA32F texel "
       << "stored by a compute shader costs " << fixed(storeRgba / kMegapixels, 1) << " ns, "
       << fixed(storeRgba / median("1. const → RGBA32F")) << "× a fragment write of the same texel; "
       << "an R32UI texel " << fixed(median("13. compute: store each texel, R32UI") / kMegapixels, 1)
       << " ns (the store is paid per channel).\n";
    return md.str();
}

struct Options {
    int frames = 11;
    std::string scene = "builtin:bunny-spot";
    std::string out;
};

int run(const Options& o) {
    // Mesa's disk cache would serve the compiled variants of an earlier run and hide the JIT
    // time of the first frame.
    setenv("MESA_SHADER_CACHE_DISABLE", "true", 0);
    const std::string loadBefore = loadAverage();
    auto context = createOsMesaContext();
    if (!context) {
        std::cerr << "fragment_costs: " << context.error().message << "\n";
        return 1;
    }
    const std::string renderer = queryGlInfo().renderer;
    std::string sceneName = o.scene;
    Result<Scene> scene = loadScene(sceneName);
    if (!scene && sceneName == "builtin:bunny-spot") {
        std::cerr << "fragment_costs: " << scene.error().message << "; using builtin:bunny\n";
        sceneName = "builtin:bunny";
        scene = loadScene(sceneName);
    }
    if (!scene) {
        std::cerr << "fragment_costs: " << scene.error().message << "\n";
        return 2;
    }
    FragmentCosts bench(*scene, sceneName);
    std::vector<Probe> probes = bench.listProbes();
    std::cerr << "fragment_costs: " << probes.size() << " probes on " << renderer << "\n";
    measure(probes, o.frames);
    checkProbes(probes);
    bench.checkComputeProbes();
    const SceneCounts counts = bench.countSceneFragments();
    gpu::checkGlError("fragment counts");
    const std::string md = markdown(probes, counts, renderer, sceneName, o.frames, loadBefore);
    if (!o.out.empty()) {
        std::ofstream file(o.out);
        if (!(file << md)) {
            std::cerr << "fragment_costs: cannot write '" << o.out << "'\n";
            return 2;
        }
    }
    std::cout << md;
    return 0;
}

}  // namespace
}  // namespace shadow

int main(int argc, char** argv) {
    shadow::Options o;
    shadow::samples::CommandLine app{"Fragment-shader cost probes at 1280x720 (see the file header)."};
    app.add("--frames", o.frames, "timed frames per probe").range(9, 1000);
    app.add("--scene", o.scene, "scene of the overdraw probes");
    app.add("--out", o.out, "markdown file to write (also printed)");
    if (const std::optional<int> exit = app.parse(argc, argv, "fragment_costs")) return *exit;
    try {
        return shadow::run(o);
    } catch (const std::exception& e) {
        std::cerr << "fragment_costs: " << e.what() << "\n";
        return 1;
    }
}
