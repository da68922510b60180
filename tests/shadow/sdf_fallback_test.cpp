// Technique sdf on the meshes games have, against the ray-traced truth: an open box (a room's
// one-sided walls, a bowl: one mesh, not closed, not flat), a caster of two such open parts, and
// closed plates 1, 3 and 10 cm thick two metres above the ground under a wide disk light. A
// distance field holds no inside for the open ones, and too few voxels inside for the thinnest:
// they cast through the light's shadow map (filtered as PCSS) with one `CasterWithoutField`
// warning, the rest is marched. Each must keep its umbra (interior leak under 1 %) and err
// within 1.5 times PCSS's RMSE plus 0.01.
#include <gtest/gtest.h>
#include <shadow/scene.h>

#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "render/render_test_support.h"
#include "shadow/soft_test_support.h"
#include "shadow/truth_test_support.h"
#include "test_support.h"

namespace shadow::test::sdf_fallback_test {
namespace {

constexpr int kWidth = 160;
constexpr int kHeight = 120;

/// `box` without the triangles of its face whose normal is `-axis` (an open box), and the same
/// lifted by `lift` appended when `twoParts` (a caster of two open parts).
std::shared_ptr<MeshData> openBox(const glm::vec3& halfExtents, bool twoParts) {
    const std::shared_ptr<MeshData> box = makeBoxMesh(halfExtents);
    auto mesh = std::make_shared<MeshData>();
    mesh->name = twoParts ? "two open boxes" : "open box";
    const int copies = twoParts ? 2 : 1;
    for (int copy = 0; copy < copies; ++copy) {
        const glm::vec3 lift(0.0f, 2.5f * halfExtents.y * static_cast<float>(copy), 0.0f);
        for (std::size_t t = 0; t + 2 < box->indices.size(); t += 3) {
            const std::uint32_t a = box->indices[t];
            // The bottom (normal -Y) is left out; the copy above is open at its top.
            const float ny = box->normals[a].y;
            if ((copy == 0 && ny < -0.5f) || (copy == 1 && ny > 0.5f)) continue;
            for (int k = 0; k < 3; ++k) {
                const std::uint32_t v = box->indices[t + static_cast<std::size_t>(k)];
                mesh->indices.push_back(static_cast<std::uint32_t>(mesh->positions.size()));
                mesh->positions.push_back(box->positions[v] + lift);
                mesh->normals.push_back(box->normals[v]);
            }
        }
    }
    computeBounds(*mesh);
    computeClosed(*mesh);
    return mesh;
}

/// A ground, `mesh` placed at `position`, and a spot 4 m up with a disk of `lightRadius` (its
/// technique set by renderAgainstTruth).
Scene casterScene(std::shared_ptr<const MeshData> mesh, const glm::dvec3& position, float lightRadius) {
    Scene scene;
    addGround(scene, 4.0f);
    addMeshInstance(scene.world, "caster", std::move(mesh), placed(position));
    Light spot = pointSizedLight(LightType::Spot, 0.7f);
    spot.radius = lightRadius;
    addLight(scene, "spot", spot, shadowWith(ShadowTechnique::Sdf, 1024), {0.3, 4.0, 0.2}, {0.0, -1.0, 0.0});
    addCamera(scene, "camera", Camera{}, {0.0, 4.5, 3.5}, {0.0, 0.0, 0.0});
    return scene;
}

void expectUmbraKept(const std::string& name, const std::shared_ptr<const MeshData>& mesh, const glm::dvec3& position,
                     float lightRadius, bool castThroughMap) {
    Scene scene = casterScene(mesh, position, lightRadius);
    const std::vector<AgainstTruth> measured =
        renderAgainstTruth(scene, kWidth, kHeight, 256, {ShadowTechnique::Sdf, ShadowTechnique::Pcss});
    const AgainstTruth& sdf = measured.at(0);
    const AgainstTruth& pcss = measured.at(1);
    std::printf("[ measured ] %s: sdf RMSE %.4f, interior leak %.4f (%lld interior umbra px); pcss RMSE %.4f\n",
                name.c_str(), sdf.errors.rmse, sdf.errors.interiorLeakFraction,
                static_cast<long long>(sdf.errors.interiorUmbraPixels), pcss.errors.rmse);
    EXPECT_GT(sdf.errors.interiorUmbraPixels, 100) << name << ": no umbra in view";
    EXPECT_LT(sdf.errors.interiorLeakFraction, 0.01) << name;
    EXPECT_LE(sdf.errors.rmse, 1.5 * pcss.errors.rmse + 0.01) << name;
    EXPECT_EQ(countWarnings(sdf.warnings, WarningCode::CasterWithoutField, "spot"), castThroughMap ? 1 : 0)
        << name << "\n"
        << describe(sdf.warnings);
}

TEST(SdfFallback, AnOpenBoxCastsThroughTheMapAndKeepsItsUmbra) {
    const std::shared_ptr<MeshData> box = openBox({0.4f, 0.4f, 0.4f}, false);
    ASSERT_FALSE(box->closed);
    ASSERT_FALSE(box->planar);
    expectUmbraKept("open box", box, {0.0, 1.2, 0.0}, 0.2f, true);
}

TEST(SdfFallback, ACasterOfTwoOpenPartsCastsThroughTheMapAndKeepsItsUmbra) {
    expectUmbraKept("two open parts", openBox({0.3f, 0.25f, 0.3f}, true), {0.0, 1.0, 0.0}, 0.2f, true);
}

TEST(SdfFallback, ThinClosedPlatesHighAboveTheGroundKeepTheirUmbraUnderAWideLight) {
    for (const double thickness : {0.01, 0.03, 0.1}) {
        const std::shared_ptr<MeshData> plate =
            makeBoxMesh(glm::vec3(0.5f, 0.5f * static_cast<float>(thickness), 0.5f));
        expectUmbraKept("closed plate " + std::to_string(thickness) + " m thick, 2 m up", plate, {0.0, 2.0, 0.0}, 0.3f,
                        thickness < 0.02);
    }
}

}  // namespace
}  // namespace shadow::test::sdf_fallback_test
