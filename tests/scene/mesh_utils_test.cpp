// Tests of computeBounds, computeClosed and makeFlatNormals (engine/src/scene/mesh_utils.cpp).
#include <gtest/gtest.h>
#include <shadow/components.h>
#include <shadow/scene.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>

namespace shadow {
namespace {

/// A unit quad in the XZ plane as two counter-clockwise triangles seen from +Y, sharing
/// vertices 0 and 2, plus a tilted triangle facing +Z.
MeshData quadAndWall() {
    MeshData mesh;
    mesh.positions = {{0, 0, 0}, {0, 0, 1}, {1, 0, 1}, {1, 0, 0}, {0, 0, -2}, {1, 0, -2}, {0, 1, -2}};
    mesh.indices = {0, 1, 2, 0, 2, 3, 4, 5, 6};
    return mesh;
}

TEST(MeshUtils, ComputeBoundsCoversEveryPosition) {
    MeshData mesh = quadAndWall();
    computeBounds(mesh);
    EXPECT_EQ(mesh.bounds.min, glm::vec3(0, 0, -2));
    EXPECT_EQ(mesh.bounds.max, glm::vec3(1, 1, 1));
}

TEST(MeshUtils, ComputeBoundsOfNoPositionsIsEmpty) {
    MeshData mesh;
    mesh.bounds.extend(glm::vec3(1.0f));
    computeBounds(mesh);
    EXPECT_TRUE(mesh.bounds.empty());
}

TEST(MeshUtils, ComputeBoundsSkipsNonFinitePositions) {
    MeshData mesh;
    mesh.positions = {
        {1, 2, 3}, {std::numeric_limits<float>::quiet_NaN(), 0, 0}, {std::numeric_limits<float>::infinity(), 0, 0}};
    computeBounds(mesh);
    EXPECT_EQ(mesh.bounds.min, glm::vec3(1, 2, 3));
    EXPECT_EQ(mesh.bounds.max, glm::vec3(1, 2, 3));
}

TEST(MeshUtils, FlatNormalsGiveEachTriangleItsOwnVertices) {
    MeshData mesh = quadAndWall();
    makeFlatNormals(mesh);
    ASSERT_EQ(mesh.positions.size(), 9u);
    ASSERT_EQ(mesh.normals.size(), 9u);
    for (std::uint32_t i = 0; i < 9; ++i) EXPECT_EQ(mesh.indices[i], i);
    for (int i = 0; i < 6; ++i) EXPECT_EQ(mesh.normals[static_cast<std::size_t>(i)], glm::vec3(0, 1, 0));
    for (int i = 6; i < 9; ++i) EXPECT_EQ(mesh.normals[static_cast<std::size_t>(i)], glm::vec3(0, 0, 1));
    EXPECT_EQ(mesh.positions[3], glm::vec3(0, 0, 0));  // second triangle starts at old vertex 0
    EXPECT_EQ(mesh.positions[5], glm::vec3(1, 0, 0));
    EXPECT_EQ(mesh.bounds.min, glm::vec3(0, 0, -2));
    EXPECT_EQ(mesh.bounds.max, glm::vec3(1, 1, 1));
}

TEST(MeshUtils, FlatNormalsOfTinyTriangleAreUnit) {
    MeshData mesh;
    mesh.positions = {{0, 0, 0}, {1e-20f, 0, 0}, {0, 1e-20f, 0}};  // cross product underflows in float
    mesh.indices = {0, 1, 2};
    makeFlatNormals(mesh);
    EXPECT_NEAR(mesh.normals[0].z, 1.0f, 1e-6f);
}

TEST(MeshUtils, DegenerateTriangleGetsAUnitNormal) {
    MeshData mesh;
    mesh.positions = {{0, 0, 0}, {1, 1, 1}, {2, 2, 2}};
    mesh.indices = {0, 1, 2};
    makeFlatNormals(mesh);
    ASSERT_EQ(mesh.normals.size(), 3u);
    EXPECT_NEAR(glm::length(mesh.normals[0]), 1.0f, 1e-6f);
}

TEST(MeshUtils, FlatNormalsDropTrianglesWithBadIndices) {
    MeshData mesh = quadAndWall();
    mesh.indices = {0, 1, 2, 0, 2, 99, 4, 5, 6, 1};  // one bad triangle, one stray index
    makeFlatNormals(mesh);
    EXPECT_EQ(mesh.positions.size(), 6u);
    EXPECT_EQ(mesh.indices.size(), 6u);
    EXPECT_EQ(mesh.normals[3], glm::vec3(0, 0, 1));
}

/// Where `farTetrahedron` stands.
const glm::vec3 kFar(1e5f, -3e4f, 7e3f);

/// A unit tetrahedron at `kFar`, wound counter-clockwise seen from outside, `closed` computed.
MeshData farTetrahedron() {
    MeshData tet;
    tet.positions = {kFar, kFar + glm::vec3(1, 0, 0), kFar + glm::vec3(0, 1, 0), kFar + glm::vec3(0, 0, 1)};
    tet.indices = {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3};
    computeClosed(tet);
    return tet;
}

/// The unit box with flat normals (every triangle its own vertices), `closed` computed.
MeshData flatBox() {
    MeshData flat = *makeBoxMesh(glm::vec3(1.0f));
    makeFlatNormals(flat);
    computeClosed(flat);
    return flat;
}

TEST(MeshUtils, ComputeClosedKnowsWatertightMeshesFromOpenOnes) {
    // The generated meshes: the box and the sphere are closed (the sphere's pole vertices and
    // seam repeat positions, welded), the plane is not.
    EXPECT_TRUE(makeBoxMesh(glm::vec3(0.5f, 0.2f, 1.0f))->closed);
    EXPECT_TRUE(makeSphereMesh(0.5f, 48, 24)->closed);
    EXPECT_TRUE(makeSphereMesh(1e-3f, 8, 4)->closed);
    EXPECT_FALSE(makePlaneMesh(2.0f, 4)->closed);

    // The box with flat normals (every triangle its own vertices) is still closed.
    EXPECT_TRUE(flatBox().closed);

    // One face missing: open. One face doubled: an edge of four triangles, not closed either.
    MeshData box = *makeBoxMesh(glm::vec3(1.0f));
    MeshData missing = box;
    missing.indices.resize(missing.indices.size() - 6);
    computeClosed(missing);
    EXPECT_FALSE(missing.closed);
    MeshData doubled = box;
    doubled.indices.insert(doubled.indices.end(), box.indices.begin(), box.indices.begin() + 6);
    computeClosed(doubled);
    EXPECT_FALSE(doubled.closed);

    // Degenerate triangles are ignored; an empty mesh is not closed; bad indices are skipped.
    MeshData degenerate = box;
    degenerate.indices.insert(degenerate.indices.end(), {0, 0, 1});
    computeClosed(degenerate);
    EXPECT_TRUE(degenerate.closed);
    MeshData empty;
    computeClosed(empty);
    EXPECT_FALSE(empty.closed);
    MeshData outOfRange = box;
    outOfRange.indices.insert(outOfRange.indices.end(), {0, 1, 100000});
    computeClosed(outOfRange);
    EXPECT_TRUE(outOfRange.closed);

    // A tetrahedron far from the origin, and the same with one vertex 1e-9 of the extent off
    // its twin (welded) and 1e-3 off (not).
    const MeshData tet = farTetrahedron();
    EXPECT_TRUE(tet.closed);
    MeshData split;
    split.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1e-9f, 0, 0}, {1e-3f, 0, 0}};
    split.indices = {0, 2, 1, 4, 1, 3, 0, 3, 2, 1, 2, 3};
    computeClosed(split);
    EXPECT_TRUE(split.closed);
    split.indices = {0, 2, 1, 5, 1, 3, 0, 3, 2, 1, 2, 3};
    computeClosed(split);
    EXPECT_FALSE(split.closed);
}

// Thickness = 2 x volume / area: a slab's thickness (to its edges' share of the area), two thirds
// of a sphere's radius (the UV sphere's facets a little under); 0 for an open mesh. Planar: every
// vertex in one plane, turned or not.
TEST(MeshUtils, ThicknessAndPlanarity) {
    const auto slab = makeBoxMesh({1.0f, 0.01f, 1.0f});
    EXPECT_NEAR(slab->thickness, 2.0 * (2.0 * 0.02 * 2.0) / (2.0 * 4.0 + 4.0 * 2.0 * 0.02), 1e-5);
    EXPECT_FALSE(slab->planar);
    const auto sphere = makeSphereMesh(1.5f, 64, 32);
    EXPECT_NEAR(sphere->thickness, 1.0, 0.01);
    const auto plane = makePlaneMesh(2.0f, 3);
    EXPECT_EQ(plane->thickness, 0.0f);
    EXPECT_TRUE(plane->planar);
    MeshData turned = *plane;
    for (glm::vec3& p : turned.positions) p = glm::vec3(p.x, 0.6f * p.z + 3.0f, 0.8f * p.z);  // a tilted plane
    computeBounds(turned);
    computeClosed(turned);
    EXPECT_TRUE(turned.planar);
    turned.positions[0].y += 0.01f;  // one vertex 1 cm off its plane
    computeClosed(turned);
    EXPECT_FALSE(turned.planar);
}

TEST(MeshUtils, SolidMeansClosedWoundAlikeAndOutwardInEveryPart) {
    // The generated closed meshes are wound counter-clockwise seen from outside.
    EXPECT_TRUE(makeBoxMesh(glm::vec3(0.5f, 0.2f, 1.0f))->solid);
    EXPECT_TRUE(makeSphereMesh(0.5f, 48, 24)->solid);
    EXPECT_FALSE(makePlaneMesh(2.0f, 4)->solid);
    EXPECT_TRUE(flatBox().solid);

    // The tetrahedron far from the origin (its volume 1/6 in double about its centre), and the
    // same turned inside out: closed, not solid.
    const MeshData tet = farTetrahedron();
    EXPECT_TRUE(tet.solid);
    MeshData inverted = tet;
    for (std::size_t t = 0; t < inverted.indices.size(); t += 3)
        std::swap(inverted.indices[t + 1], inverted.indices[t + 2]);
    computeClosed(inverted);
    EXPECT_TRUE(inverted.closed);
    EXPECT_FALSE(inverted.solid);

    // One face of four wound the other way: every edge still has two triangles, but one of its
    // edges runs the same way in both.
    MeshData oneFlipped = tet;
    std::swap(oneFlipped.indices[1], oneFlipped.indices[2]);
    computeClosed(oneFlipped);
    EXPECT_TRUE(oneFlipped.closed);
    EXPECT_FALSE(oneFlipped.solid);

    // Two parts in one mesh: solid when both are outward, not when either is inside out, though
    // the sum of their volumes is positive (the outward part is the larger).
    MeshData two = *makeBoxMesh(glm::vec3(1.0f));
    const std::uint32_t base = static_cast<std::uint32_t>(two.positions.size());
    for (const glm::vec3& p : tet.positions) two.positions.push_back(p - kFar + glm::vec3(5.0f, 0.0f, 0.0f));
    two.normals.resize(two.positions.size(), glm::vec3(0.0f, 1.0f, 0.0f));
    for (std::uint32_t i : tet.indices) two.indices.push_back(base + i);
    computeClosed(two);
    EXPECT_TRUE(two.solid);
    for (std::size_t t = two.indices.size() - tet.indices.size(); t < two.indices.size(); t += 3)
        std::swap(two.indices[t + 1], two.indices[t + 2]);
    computeClosed(two);
    EXPECT_TRUE(two.closed);
    EXPECT_FALSE(two.solid);

    // A non-finite position leaves the sign of its part unknown: not solid.
    MeshData broken = tet;
    broken.positions[3].z = std::numeric_limits<float>::quiet_NaN();
    computeClosed(broken);
    EXPECT_FALSE(broken.solid);
}

}  // namespace
}  // namespace shadow
