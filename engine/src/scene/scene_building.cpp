// Building scenes in code: primitive meshes, instances, lights, cameras, camera views.
#include <shadow/scene.h>

#include "scene/default_camera.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>

namespace shadow {

std::shared_ptr<MeshData> makeBoxMesh(const glm::vec3& halfExtents) {
    auto mesh = std::make_shared<MeshData>();
    mesh->name = "box";
    // Each face: normal axis, and the two axes spanning it (counter-clockwise seen from outside).
    for (int axis = 0; axis < 3; ++axis) {
        for (int sign = -1; sign <= 1; sign += 2) {
            glm::vec3 n(0.0f);
            n[axis] = static_cast<float>(sign);
            const int u = (axis + 1) % 3;
            const int v = (axis + 2) % 3;
            const auto base = static_cast<std::uint32_t>(mesh->positions.size());
            for (int k = 0; k < 4; ++k) {
                glm::vec3 p(0.0f);
                p[axis] = n[axis] * halfExtents[axis];
                p[u] = ((k == 1 || k == 2) ? 1.0f : -1.0f) * halfExtents[u];
                p[v] = (k >= 2 ? 1.0f : -1.0f) * halfExtents[v];
                mesh->positions.push_back(p);
                mesh->normals.push_back(n);
            }
            // (u,v) = (-,-), (+,-), (+,+), (-,+); u x v = +axis, so flip the winding for sign < 0.
            if (sign > 0) {
                mesh->indices.insert(mesh->indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
            } else {
                mesh->indices.insert(mesh->indices.end(), {base, base + 2, base + 1, base, base + 3, base + 2});
            }
        }
    }
    computeBounds(*mesh);
    computeClosed(*mesh);
    return mesh;
}

std::shared_ptr<MeshData> makePlaneMesh(float halfSize, int cells) {
    auto mesh = std::make_shared<MeshData>();
    mesh->name = "plane";
    cells = std::max(cells, 1);
    for (int j = 0; j <= cells; ++j) {
        for (int i = 0; i <= cells; ++i) {
            const float x = -halfSize + 2.0f * halfSize * static_cast<float>(i) / static_cast<float>(cells);
            const float z = -halfSize + 2.0f * halfSize * static_cast<float>(j) / static_cast<float>(cells);
            mesh->positions.emplace_back(x, 0.0f, z);
            mesh->normals.emplace_back(0.0f, 1.0f, 0.0f);
        }
    }
    const auto row = static_cast<std::uint32_t>(cells + 1);
    for (std::uint32_t j = 0; j < static_cast<std::uint32_t>(cells); ++j) {
        for (std::uint32_t i = 0; i < static_cast<std::uint32_t>(cells); ++i) {
            const std::uint32_t a = j * row + i;
            // Counter-clockwise seen from +Y.
            mesh->indices.insert(mesh->indices.end(), {a, a + row, a + 1, a + 1, a + row, a + row + 1});
        }
    }
    computeBounds(*mesh);
    computeClosed(*mesh);
    return mesh;
}

std::shared_ptr<MeshData> makeSphereMesh(float radius, int segments, int rings) {
    auto mesh = std::make_shared<MeshData>();
    mesh->name = "sphere";
    segments = std::max(segments, 3);
    rings = std::max(rings, 2);
    constexpr double kPi = 3.14159265358979323846;
    for (int r = 0; r <= rings; ++r) {
        const double theta = kPi * r / rings;
        for (int s = 0; s <= segments; ++s) {
            const double phi = 2.0 * kPi * s / segments;
            const glm::vec3 n(static_cast<float>(std::sin(theta) * std::cos(phi)), static_cast<float>(std::cos(theta)),
                              static_cast<float>(std::sin(theta) * std::sin(phi)));
            mesh->positions.push_back(n * radius);
            mesh->normals.push_back(n);
        }
    }
    const auto row = static_cast<std::uint32_t>(segments + 1);
    for (std::uint32_t r = 0; r < static_cast<std::uint32_t>(rings); ++r) {
        for (std::uint32_t s = 0; s < static_cast<std::uint32_t>(segments); ++s) {
            const std::uint32_t a = r * row + s;
            mesh->indices.insert(mesh->indices.end(), {a, a + 1, a + row, a + 1, a + row + 1, a + row});
        }
    }
    computeBounds(*mesh);
    computeClosed(*mesh);
    return mesh;
}

glm::dquat rotationLookingAlong(const glm::dvec3& direction) {
    const glm::dmat4 viewFromWorld = lookAlong(glm::dvec3(0.0), direction);
    return glm::quat_cast(glm::transpose(glm::dmat3(viewFromWorld)));
}

Entity addMeshInstance(World& world, const std::string& name, std::shared_ptr<const MeshData> mesh,
                       const Transform& transform, const Material& material) {
    const Entity e = world.create();
    world.emplace<Name>(e, Name{name});
    world.emplace<Transform>(e, transform);
    world.emplace<Mesh>(e, Mesh{std::move(mesh), true, true});
    world.emplace<Material>(e, material);
    return e;
}

Entity addLight(Scene& scene, const std::string& name, const Light& light, const Shadow& shadow,
                const glm::dvec3& position, const glm::dvec3& direction) {
    World& world = scene.world;
    const Entity e = world.create();
    world.emplace<Name>(e, Name{name});
    Transform t;
    t.translation = position;
    t.rotation = rotationLookingAlong(direction);
    world.emplace<Transform>(e, t);
    world.emplace<Light>(e, light);
    if (shadow.technique != ShadowTechnique::None) world.emplace<Shadow>(e, shadow);
    scene.lights.push_back(e);
    return e;
}

Entity addCamera(Scene& scene, const std::string& name, const Camera& camera, const glm::dvec3& position,
                 const glm::dvec3& target) {
    World& world = scene.world;
    const Entity e = world.create();
    world.emplace<Name>(e, Name{name});
    Transform t;
    t.translation = position;
    const glm::dvec3 d = target - position;
    t.rotation = rotationLookingAlong(glm::length(d) > 0.0 ? d : glm::dvec3(0, 0, -1));
    world.emplace<Transform>(e, t);
    world.emplace<Camera>(e, camera);
    scene.cameras.push_back(e);
    return e;
}

CameraView makeCameraView(const World& world, Entity camera, float imageAspect) {
    CameraView v;
    const Camera* cam = world.tryGet<Camera>(camera);
    const WorldTransform* wt = world.tryGet<WorldTransform>(camera);
    if (cam != nullptr) {
        v.yfov = std::clamp(cam->yfov, 1e-4f, 3.1414f);
        v.znear = std::max(cam->znear, 1e-6f);
        v.zfar = std::max(cam->zfar, v.znear * 2.0f);
        v.aspect = cam->aspectRatio > 0.0f ? cam->aspectRatio : imageAspect;
    } else {
        v.aspect = imageAspect;
    }
    if (!(v.aspect > 0.0f) || !std::isfinite(v.aspect)) v.aspect = 1.0f;
    if (wt == nullptr || !wt->finite) return v;
    // Rigid part of the node's matrix, scale ignored: the lights' rule (worldOrientation).
    const glm::dmat4& m = wt->worldFromLocal;
    glm::dmat4 worldFromView(worldOrientation(*wt));
    worldFromView[3] = m[3];
    v.wsPosition = glm::dvec3(m[3]);
    v.viewFromWorld = glm::inverse(worldFromView);
    return v;
}

Entity addDefaultCamera(Scene& scene) {
    DAabb bounds;
    scene.world.view<WorldBounds>().each([&](Entity, WorldBounds& wb) { bounds.extend(wb.box); });
    if (bounds.empty()) {
        bounds.extend(glm::dvec3(-1.0));
        bounds.extend(glm::dvec3(1.0));
    }
    Camera camera;
    const glm::dvec3 center = bounds.center();
    const double radius = std::max(0.5 * glm::length(bounds.extent()), 1e-3);
    const double distance = 1.1 * radius / std::tan(0.5 * camera.yfov);
    const glm::dvec3 eye = center + glm::normalize(defaultCameraOffset()) * distance;
    camera.znear = static_cast<float>(std::max(distance - radius, distance * 1e-3) * 0.5);
    camera.zfar = static_cast<float>((distance + radius) * 1.5);
    return addCamera(scene, "default camera", camera, eye, center);
}

}  // namespace shadow
