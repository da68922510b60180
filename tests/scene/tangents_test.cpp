// Texture-space helpers of materials (engine/src/scene/tangents.cpp): the KHR_texture_transform
// matrix and normal-map tangents, against the uv mapping's own derivatives.
#include <gtest/gtest.h>
#include <shadow/scene.h>

#include <algorithm>
#include <cmath>

namespace shadow {
namespace {

// uv' = offset + R(rotation) * (scale * uv), R turning +u towards -v (the extension's sense).
TEST(Tangents, TextureTransformIsTheExtensionsMatrix) {
    const glm::mat3x2 m = textureTransform({0.25f, -0.5f}, 1.5707963f, {2.0f, 3.0f});
    const glm::vec2 u = m * glm::vec3(1.0f, 0.0f, 1.0f), v = m * glm::vec3(0.0f, 1.0f, 1.0f);
    EXPECT_NEAR(u.x, 0.25f, 1e-6f);
    EXPECT_NEAR(u.y, -0.5f - 2.0f, 1e-6f);
    EXPECT_NEAR(v.x, 0.25f + 3.0f, 1e-6f);
    EXPECT_NEAR(v.y, -0.5f, 1e-6f);
}

// On a plane whose u runs along +Z and v along -X, the tangent is +Z and the handedness makes
// w x cross(normal, tangent) the -X of +v: w = -1. Mirroring u flips the tangent and w.
TEST(Tangents, FollowTheUvMappingAndItsHandedness) {
    for (const float mirror : {1.0f, -1.0f}) {
        std::shared_ptr<MeshData> plane = makePlaneMesh(1.0f, 3);
        for (const glm::vec3& p : plane->positions) plane->texcoords.emplace_back(mirror * p.z, -p.x);
        computeTangents(*plane, 0);
        ASSERT_EQ(plane->tangents.size(), plane->positions.size());
        for (std::size_t i = 0; i < plane->tangents.size(); ++i) {
            const glm::vec4 t = plane->tangents[i];
            EXPECT_NEAR(t.x, 0.0f, 1e-5f);
            EXPECT_NEAR(t.z, mirror, 1e-5f);
            const glm::vec3 bitangent = t.w * glm::cross(plane->normals[i], glm::vec3(t));
            EXPECT_NEAR(bitangent.x, -1.0f, 1e-5f) << "vertex " << i << " mirror " << mirror;
        }
    }
}

// A sphere's tangents are unit and perpendicular to its normals everywhere, poles included
// (where the uv mapping collapses), and none is NaN.
TEST(Tangents, AreUnitAndPerpendicularOnASphere) {
    std::shared_ptr<MeshData> sphere = makeSphereMesh(1.0f, 16, 8);
    for (const glm::vec3& p : sphere->positions) {
        sphere->texcoords.emplace_back(std::atan2(p.z, p.x) / 6.2831853f + 0.5f,
                                       std::acos(std::clamp(p.y, -1.0f, 1.0f)) / 3.1415927f);
    }
    computeTangents(*sphere, 0);
    ASSERT_EQ(sphere->tangents.size(), sphere->positions.size());
    for (std::size_t i = 0; i < sphere->tangents.size(); ++i) {
        const glm::vec3 t(sphere->tangents[i]);
        EXPECT_NEAR(glm::length(t), 1.0f, 1e-4f) << "vertex " << i;
        EXPECT_NEAR(glm::dot(t, sphere->normals[i]), 0.0f, 1e-4f) << "vertex " << i;
        EXPECT_EQ(std::abs(sphere->tangents[i].w), 1.0f);
    }
}

TEST(Tangents, NoneWithoutTheirTexcoordSet) {
    std::shared_ptr<MeshData> plane = makePlaneMesh(1.0f, 1);
    computeTangents(*plane, 1);
    EXPECT_TRUE(plane->tangents.empty());
}

}  // namespace
}  // namespace shadow
