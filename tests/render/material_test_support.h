// What the material tests share: textured planes and images made in the test, a camera and a
// light whose geometry is known, and lighting.glsl's shading of one light in closed form on the
// CPU (the GGX lobe, Schlick's Fresnel, the diffuse weighted by 1 - F).
//
// Header-only on purpose: tests/CMakeLists.txt globs only *_test.cpp files.
#pragma once

#include <shadow/frame_runner.h>
#include <shadow/scene.h>

#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
#include <functional>
#include <memory>
#include <string>

#include "render/render_test_support.h"

namespace shadow::test {

/// A `size` x `size` RGBA8 texture whose texel (x, y) (y = 0 the first row, v = 0) is `texel(u, v)`
/// at the texel's centre, clamped to its edges (so that the plane's border reads no wrapped texel).
inline std::shared_ptr<const Texture> makeTexture(const std::string& name, int size,
                                                  const std::function<glm::u8vec4(float, float)>& texel) {
    auto t = std::make_shared<Texture>();
    t->name = name;
    t->width = size;
    t->height = size;
    t->wrapS = Texture::Wrap::ClampToEdge;
    t->wrapT = Texture::Wrap::ClampToEdge;
    for (int y = 0; y < size; ++y) {
        for (int x = 0; x < size; ++x) {
            const glm::u8vec4 c = texel((static_cast<float>(x) + 0.5f) / static_cast<float>(size),
                                        (static_cast<float>(y) + 0.5f) / static_cast<float>(size));
            t->rgba.insert(t->rgba.end(), {c.r, c.g, c.b, c.a});
        }
    }
    return t;
}

/// A square in the XZ plane (normal +Y) of half edge `halfSize`, `cells` x `cells` quads, with
/// u = (x / halfSize + 1) / 2 and v = (z / halfSize + 1) / 2, and its tangents (+X, handedness
/// such that the bitangent is +Z, along +v).
inline std::shared_ptr<MeshData> makeTexturedPlane(float halfSize, int cells = 4) {
    std::shared_ptr<MeshData> mesh = makePlaneMesh(halfSize, cells);
    for (const glm::vec3& p : mesh->positions) {
        mesh->texcoords.emplace_back((p.x / halfSize + 1.0f) / 2.0f, (p.z / halfSize + 1.0f) / 2.0f);
    }
    computeTangents(*mesh, 0);
    return mesh;
}

/// The u of world x on `makeTexturedPlane(halfSize)`.
inline double planeU(double x, double halfSize) { return (x / halfSize + 1.0) / 2.0; }

/// glTF's parameters of a material with maps (the loader's derived fields filled alike).
inline Material gltfMaterial(const glm::vec3& base, float metallic, float roughness) {
    Material m;
    m.baseColor = base;
    m.metallic = metallic;
    m.roughness = roughness;
    m.albedo = base * (1.0f - metallic);
    m.specular = glm::mix(glm::vec3(0.04f), base, metallic);
    const float a2 = std::max(std::pow(roughness, 4.0f), 1e-4f);
    m.shininess = std::clamp(2.0f / a2 - 2.0f, 1.0f, 4096.0f);
    return m;
}

/// What a surface reflects of one light, as shaders/lighting.glsl's shadeSurface computes it.
struct ClosedFormSurface {
    glm::dvec3 normal{0.0, 1.0, 0.0};  ///< unit
    glm::dvec3 albedo{0.0};
    glm::dvec3 specular{0.04};
    double shininess = 1.0;
};

/// Radiance towards unit `toViewer` under a directional light of illuminance `lux` (colour 1)
/// arriving from unit `toLight`.
inline glm::dvec3 shadeClosedForm(const ClosedFormSurface& s, const glm::dvec3& toLight, const glm::dvec3& toViewer,
                                  double lux) {
    constexpr double kPi = 3.14159265358979323846;
    const double nDotL = glm::dot(s.normal, toLight);
    if (nDotL <= 0.0) return glm::dvec3(0.0);
    const glm::dvec3 h = glm::normalize(toLight + toViewer);
    const double nDotV = std::max(glm::dot(s.normal, toViewer), 1e-4);
    const double nDotH = std::max(glm::dot(s.normal, h), 0.0);
    const double a2 = 2.0 / (s.shininess + 2.0);
    const double q = nDotH * nDotH * (a2 - 1.0) + 1.0;
    const double distribution = a2 / (kPi * q * q);
    const double visibility =
        0.5 / (nDotL * std::sqrt(nDotV * nDotV * (1.0 - a2) + a2) + nDotV * std::sqrt(nDotL * nDotL * (1.0 - a2) + a2));
    const double m = 1.0 - std::max(glm::dot(toViewer, h), 0.0);
    const glm::dvec3 fresnel = s.specular + (1.0 - s.specular) * (m * m * m * m * m);
    const glm::dvec3 brdf = s.albedo / kPi * (1.0 - fresnel) + distribution * visibility * fresnel;
    return lux * nDotL * brdf;
}

/// What a surface reflects under a uniform ambient radiance `ambient` (both hemispheres alike),
/// as shaders/lighting.glsl's ambientShading computes it: the diffuse albedo's share and the
/// split sum's directional albedo in Karis' analytic fit, at `nDotV` (cosine of the view).
inline double ambientClosedForm(double albedo, double f0, double shininess, double nDotV, double ambient) {
    const double alpha = std::sqrt(2.0 / (shininess + 2.0));
    const double roughness = std::sqrt(alpha);
    const glm::dvec4 q = roughness * glm::dvec4(-1.0, -0.0275, -0.572, 0.022) + glm::dvec4(1.0, 0.0425, 1.04, -0.04);
    const double a004 = std::min(q.x * q.x, std::exp2(-9.28 * std::max(nDotV, 1e-4))) * q.x + q.y;
    const double w = f0 * (-1.04 * a004 + q.z) + (1.04 * a004 + q.w);
    return ambient * (albedo * (1.0 - w) + w);
}

/// The sRGB byte `b` as the GPU decodes it (linear).
inline double srgbToLinear(int b) {
    const double c = b / 255.0;
    return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

/// A scene of `mesh` with `material` at the origin, a camera 4 m above it looking down (tilted a
/// little, so that no lobe points at it), and, when `lux` > 0, a sun arriving from `toLight`
/// without shadows.
inline Scene materialScene(const std::shared_ptr<const MeshData>& mesh, const Material& material,
                           const glm::dvec3& toLight, float lux) {
    Scene scene;
    addMeshInstance(scene.world, "plane", mesh, placed(glm::dvec3(0.0)), material);
    addCamera(scene, "camera", Camera{}, {0.0, 4.0, 0.6}, {0.0, 0.0, 0.0});
    if (lux > 0.0f) {
        Light sun;
        sun.type = LightType::Directional;
        sun.intensity = lux;
        Shadow none;
        none.technique = ShadowTechnique::None;
        addLight(scene, "sun", sun, none, toLight * 10.0, -toLight);
    }
    return scene;
}

/// One frame of `scene` with AOVs, the given ambient, forward or through the stage.
inline FrameImages renderMaterialScene(Scene& scene, int width, int height, const glm::vec3& ambient,
                                       ScreenVisibility where = ScreenVisibility::Off) {
    glContext();
    FrameRunner runner;
    RenderOptions options;
    options.width = width;
    options.height = height;
    options.aovs = true;
    options.ambientSky = ambient;
    options.ambientGround = ambient;
    options.screenVisibility = where;
    FrameStats stats = runner.runFrame(scene, 0.0, scene.cameras.at(0), options);
    return runner.renderer().readback(runner.lastCamera(), stats);
}

}  // namespace shadow::test
