// Shared helpers of the GL tests: one headless context per process, rendering a scene through
// FrameRunner with AOVs, building small test scenes, and the geometric truth of hard shadows.
//
// Header-only on purpose: tests/CMakeLists.txt globs only *_test.cpp files.
#pragma once

#include <gtest/gtest.h>
#include <shadow/context.h>
#include <shadow/context_osmesa.h>
#include <shadow/frame_runner.h>
#include <shadow/scene.h>
#include <shadow/shadow_system.h>

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace shadow::test {

/// The process-wide OSMesa context (created on first use, current on return). Every GL test
/// calls this before touching GL; libOSMesa allows one provider per process, so one context
/// serves them all.
inline GlContext& glContext() {
    static const std::unique_ptr<GlContext> context = [] {
        Result<std::unique_ptr<GlContext>> made = createOsMesaContext();
        if (!made) throw std::runtime_error("cannot create the OSMesa context: " + made.error().message);
        return std::move(made.value());
    }();
    context->makeCurrent();
    return *context;
}

/// One rendered frame: the images and the counters of that frame.
struct RenderedFrame {
    FrameImages images;
    FrameStats stats;
};

/// Runs one frame of `scene` at time `t` through `runner` with `options` and AOVs, and reads it
/// back. The camera is the scene's first unless `camera` names another.
inline RenderedFrame renderFrame(FrameRunner& runner, Scene& scene, RenderOptions options, double t = 0.0,
                                 Entity camera = Entity::null()) {
    glContext();
    if (camera.isNull()) camera = scene.cameras.at(0);
    options.aovs = true;
    RenderedFrame out;
    out.stats = runner.runFrame(scene, t, camera, options);
    out.images = runner.renderer().readback(runner.lastCamera(), out.stats);
    return out;
}

/// `renderFrame` at `width` x `height` with the default options.
inline RenderedFrame renderFrame(FrameRunner& runner, Scene& scene, int width, int height, double t = 0.0,
                                 Entity camera = Entity::null()) {
    RenderOptions options;
    options.width = width;
    options.height = height;
    return renderFrame(runner, scene, options, t, camera);
}

/// `renderFrame` with a fresh runner (a first frame: everything compiled and drawn).
inline FrameImages renderOnce(Scene& scene, int width, int height) {
    glContext();
    FrameRunner runner;
    return renderFrame(runner, scene, width, height).images;
}

/// A transform at `position` scaled by `scale`.
inline Transform placed(const glm::dvec3& position, const glm::dvec3& scale = glm::dvec3(1.0)) {
    Transform t;
    t.translation = position;
    t.scale = scale;
    return t;
}

/// A square ground plane at y = 0, centred on the origin.
inline Entity addGround(Scene& scene, float halfSize) {
    return addMeshInstance(scene.world, "ground", makePlaneMesh(halfSize, 4), placed(glm::dvec3(0.0)));
}

/// An axis-aligned box of `halfExtents` centred at `center`; returns its entity.
inline Entity addBox(Scene& scene, const std::string& name, const glm::dvec3& center, const glm::dvec3& halfExtents) {
    return addMeshInstance(scene.world, name, makeBoxMesh(glm::vec3(halfExtents)), placed(center));
}

/// Hard-shadow settings (technique Hard) with the given map size.
inline Shadow hardShadow(int mapSize = 1024) {
    Shadow s;
    s.technique = ShadowTechnique::Hard;
    s.mapSize = mapSize;
    return s;
}

/// A light of `type` with a point-sized emitter (hard shadows are exact for it).
inline Light pointSizedLight(LightType type, float outerConeAngle = 0.7f) {
    Light l;
    l.type = type;
    l.intensity = type == LightType::Directional ? 3.0f : 20.0f;
    l.radius = 0.0f;
    l.angularRadius = 0.0f;
    l.outerConeAngle = outerConeAngle;
    l.innerConeAngle = 0.5f * outerConeAngle;
    return l;
}

/// Whether the segment `origin + t * dir`, t in (tMin, tMax), meets the closed box (slab test in
/// double; `dir` need not be unit).
inline bool segmentHitsBox(const glm::dvec3& origin, const glm::dvec3& dir, double tMin, double tMax,
                           const DAabb& box) {
    for (int a = 0; a < 3; ++a) {
        if (std::abs(dir[a]) < 1e-300) {
            if (origin[a] < box.min[a] || origin[a] > box.max[a]) return false;
            continue;
        }
        double t0 = (box.min[a] - origin[a]) / dir[a];
        double t1 = (box.max[a] - origin[a]) / dir[a];
        if (t0 > t1) std::swap(t0, t1);
        tMin = std::max(tMin, t0);
        tMax = std::min(tMax, t1);
        if (tMin > tMax) return false;
    }
    return true;
}

/// Where a light is, as the analytic shadow needs it.
struct AnalyticLight {
    LightType type = LightType::Point;
    glm::dvec3 position{0.0};
    glm::dvec3 direction{0.0, -1.0, 0.0};  ///< unit, the way the light shines (directional)
};

/// True when the point `p` sees the light past every box in `boxes`: the ray from `p` to the
/// light position (point/spot) or along -direction (directional) misses them all.
template <typename Boxes>
bool analyticallyLit(const AnalyticLight& light, const glm::dvec3& p, const Boxes& boxes) {
    const bool directional = light.type == LightType::Directional;
    const glm::dvec3 dir = directional ? -light.direction : light.position - p;
    const double tMax = directional ? std::numeric_limits<double>::infinity() : 1.0;
    for (const DAabb& box : boxes) {
        if (segmentHitsBox(p, dir, 1e-9, tMax, box)) return false;
    }
    return true;
}

/// The world box of a box mesh instance of `halfExtents` centred at `center`.
inline DAabb boxBounds(const glm::dvec3& center, const glm::dvec3& halfExtents) {
    DAabb b;
    b.extend(center - halfExtents);
    b.extend(center + halfExtents);
    return b;
}

/// Whether a pixel of `images.position` is ground (covered and at y = 0).
inline bool isGroundPixel(const FrameImages& images, int x, int y) {
    return images.position.at(x, y, 3) > 0.5f && std::abs(images.position.at(x, y, 1)) < 1e-3f;
}

/// The world point seen at pixel (x, y) of the position AOV.
inline glm::dvec3 positionAt(const FrameImages& images, int x, int y) {
    return {images.position.at(x, y, 0), images.position.at(x, y, 1), images.position.at(x, y, 2)};
}

/// Layer of a light's array a receiver at `p` uses (point: cube face as the shader's cubeFace).
inline int layerOf(const ShadowLightPlan& plan, const glm::dvec3& p) {
    if (plan.light.type != LightType::Point) return 0;
    const glm::dvec3 d = p - glm::dvec3(glm::inverse(plan.layers[0].lightFromWorld)[3]);
    const glm::dvec3 a = glm::abs(d);
    if (a.x >= a.y && a.x >= a.z) return d.x >= 0.0 ? 0 : 1;
    if (a.y >= a.z) return d.y >= 0.0 ? 2 : 3;
    return d.z >= 0.0 ? 4 : 5;
}

/// Size on the ground (m) of one shadow texel at ground point `p`: the texel's lateral size,
/// 2 / (clipFromLight[0][0] * mapSize), times the axial distance for perspective layers, and
/// stretched by 1 / cos(incidence) since the ground is tilted against the light's rays.
inline double groundTexelAt(const ShadowLightPlan& plan, const AnalyticLight& light, const glm::dvec3& p) {
    const ShadowLayerPlan& layer = plan.layers[static_cast<std::size_t>(layerOf(plan, p))];
    double texel = 2.0 / (layer.clipFromLight[0][0] * plan.mapSize);
    if (!layer.orthographic) texel *= std::max(-(layer.lightFromWorld * glm::dvec4(p, 1.0)).z, 0.0);
    const glm::dvec3 toLight =
        light.type == LightType::Directional ? -light.direction : glm::normalize(light.position - p);
    return texel / std::max(std::abs(toLight.y), 0.25);
}

/// How a hard shadow on the ground agrees with ray casting against boxes.
struct GeometryAgreement {
    int groundPixels = 0;
    int shadowedPixels = 0;                 ///< analytically shadowed ground pixels
    int mismatches = 0;                     ///< ground pixels where (visibility > 0.5) != analytic
    int outsideBand = 0;                    ///< of those, farther than the edge band from the analytic edge
    std::array<int, 6> shadowedPerLayer{};  ///< analytically shadowed pixels by layer (point: face)
};

/// Compares visibility AOV `visibility` with the ray-cast shadow of `boxes` over the ground
/// pixels (y = 0), skipping those outside a spot's cone of half-angle `spotCone`. A shadow map
/// places an edge only to within its texels, so pixels whose analytic answer changes within
/// `bandTexels` texel footprints (in any of 8 directions) form an edge band where either answer
/// is accepted; `outsideBand` counts the mismatches beyond it.
/// `keep`, when given, further selects the ground points compared.
template <typename Boxes>
GeometryAgreement compareWithGeometry(const FrameImages& images, const ImageF& visibility, const ShadowLightPlan& plan,
                                      const AnalyticLight& light, const Boxes& boxes, double bandTexels,
                                      double spotCone = 0.0, const std::function<bool(const glm::dvec3&)>& keep = {}) {
    GeometryAgreement m;
    for (int y = 0; y < visibility.height; ++y) {
        for (int x = 0; x < visibility.width; ++x) {
            if (!isGroundPixel(images, x, y)) continue;
            const glm::dvec3 p = positionAt(images, x, y);
            if (keep && !keep(p)) continue;
            // A spot's map covers its cone only; outside it there is no light to shadow.
            if (light.type == LightType::Spot &&
                glm::dot(glm::normalize(p - light.position), light.direction) < std::cos(spotCone)) {
                continue;
            }
            ++m.groundPixels;
            const bool lit = analyticallyLit(light, p, boxes);
            if (!lit) {
                ++m.shadowedPixels;
                ++m.shadowedPerLayer[static_cast<std::size_t>(layerOf(plan, p))];
            }
            if ((visibility.at(x, y, 0) > 0.5f) == lit) continue;
            ++m.mismatches;
            const double reach = bandTexels * groundTexelAt(plan, light, p);
            bool nearEdge = false;
            for (int k = 0; k < 8 && !nearEdge; ++k) {
                const double angle = k * 0.25 * 3.14159265358979;
                const glm::dvec3 q = p + reach * glm::dvec3(std::cos(angle), 0.0, std::sin(angle));
                nearEdge = analyticallyLit(light, q, boxes) != lit;
            }
            if (!nearEdge) ++m.outsideBand;
        }
    }
    return m;
}

/// Number of values of `image` that are NaN or Inf.
inline int countNonFinite(const ImageF& image) {
    return static_cast<int>(
        std::count_if(image.pixels.begin(), image.pixels.end(), [](float v) { return !std::isfinite(v); }));
}

/// The AOV invariants every frame must keep (docs/output_contract.md): nothing NaN/Inf, visibility in [0, 1],
/// background pixels fully lit. Adds a failure for each broken one.
inline void expectSaneAovs(const FrameImages& images) {
    ASSERT_GT(images.position.width, 0) << "AOVs were not produced";
    EXPECT_EQ(countNonFinite(images.color), 0) << "color has NaN/Inf";
    EXPECT_EQ(countNonFinite(images.position), 0) << "position has NaN/Inf";
    EXPECT_EQ(countNonFinite(images.depth), 0) << "depth has NaN/Inf";
    for (std::size_t i = 0; i < images.visibility.size(); ++i) {
        const ImageF& v = images.visibility[i];
        EXPECT_EQ(countNonFinite(v), 0) << "visibility " << i << " has NaN/Inf";
        int outOfRange = 0;
        int darkBackground = 0;
        for (int y = 0; y < v.height; ++y) {
            for (int x = 0; x < v.width; ++x) {
                const float value = v.at(x, y, 0);
                if (!(value >= 0.0f && value <= 1.0f)) ++outOfRange;
                if (images.position.at(x, y, 3) < 0.5f && value != 1.0f) ++darkBackground;
            }
        }
        EXPECT_EQ(outOfRange, 0) << "visibility " << i << " outside [0, 1]";
        EXPECT_EQ(darkBackground, 0) << "visibility " << i << " is not 1 on the background";
    }
}

/// A ground, a box, a post and three lights, one per type and filtering technique: a PCSS spot, a
/// PCF point light and a hard sun (every pass the engine has, the min/max pyramids included).
inline Scene threeLightScene() {
    Scene scene;
    addGround(scene, 3.0f);
    addBox(scene, "box", {0.0, 0.6, 0.0}, {0.4, 0.4, 0.4});
    addBox(scene, "post", {-1.2, 0.5, 0.8}, {0.1, 0.5, 0.1});
    Light spot = pointSizedLight(LightType::Spot, 0.7f);
    spot.radius = 0.15f;
    Shadow pcss = hardShadow(256);
    pcss.technique = ShadowTechnique::Pcss;
    addLight(scene, "spot", spot, pcss, {0.5, 4.0, 0.3}, {0, -1, 0});
    Shadow pcf = hardShadow(128);
    pcf.technique = ShadowTechnique::Pcf;
    addLight(scene, "bulb", pointSizedLight(LightType::Point), pcf, {-1.0, 2.0, 1.0}, {0, -1, 0});
    addLight(scene, "sun", pointSizedLight(LightType::Directional), hardShadow(256), {0, 10, 0},
             glm::normalize(glm::dvec3(0.3, -1.0, 0.2)));
    addCamera(scene, "camera", Camera{}, {0.0, 3.0, 5.0}, {0.0, 0.0, 0.0});
    return scene;
}

/// Window depth (GL's default depth range and clip control) of the surfaces of `position`, a
/// position AOV seen by `camera`, rows bottom first; 1 on the background. The mask's input, made
/// the same for every run.
inline std::vector<float> windowDepth(const ImageF& position, const CameraView& camera) {
    const glm::dmat4 clipFromWorld =
        glm::perspective(static_cast<double>(camera.yfov), static_cast<double>(camera.aspect),
                         static_cast<double>(camera.znear), static_cast<double>(camera.zfar)) *
        camera.viewFromWorld;
    std::vector<float> depth(static_cast<std::size_t>(position.width) * position.height, 1.0f);
    for (int y = 0; y < position.height; ++y) {
        for (int x = 0; x < position.width; ++x) {
            if (position.at(x, y, 3) < 0.5f) continue;
            const glm::dvec4 clip =
                clipFromWorld * glm::dvec4(position.at(x, y, 0), position.at(x, y, 1), position.at(x, y, 2), 1.0);
            depth[static_cast<std::size_t>(position.height - 1 - y) * position.width + x] =
                static_cast<float>(0.5 * clip.z / clip.w + 0.5);
        }
    }
    return depth;
}

}  // namespace shadow::test
