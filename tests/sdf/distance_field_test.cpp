// Tests of bakeDistanceField and sampleDistance (engine/src/sdf/): distances against closed forms
// (a box, a plane) and a brute-force distance to every triangle (the bunny), the sign rule on
// closed, open and flipped meshes, the grid's layout and the errors of bad input.
//
// Tolerance: a baked voxel is the exact distance from its centre, so it is compared with the
// truth to kExact of the mesh's longest extent (float rounding of coordinates and values, a few
// 1e-7); never above the truth by more than that anywhere, near the surface or far from it.
#include <gtest/gtest.h>
#include <shadow/distance_field.h>
#include <shadow/scene.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

namespace shadow {
namespace {

constexpr double kExact = 1e-5;
const double kHalfDiagonal = std::sqrt(3.0) / 2.0;

double longestExtent(const MeshData& mesh) {
    const glm::vec3 e = mesh.bounds.extent();
    return std::max({e.x, e.y, e.z});
}

/// Distance from `p` to segment [a, b].
double segmentDistance(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b) {
    const glm::dvec3 ab = b - a;
    const double t = std::clamp(glm::dot(p - a, ab) / glm::dot(ab, ab), 0.0, 1.0);
    return glm::length(p - (a + t * ab));
}

/// Distance from `p` to triangle abc, by another route than the engine's: the foot of the
/// perpendicular on the plane when it falls inside (barycentric signs), else the nearest edge.
double triangleDistance(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
    const glm::dvec3 n = glm::cross(b - a, c - a);
    const double area2 = glm::dot(n, n);
    if (area2 > 0.0) {
        const glm::dvec3 foot = p - n * (glm::dot(p - a, n) / area2);
        const bool inside = glm::dot(glm::cross(b - a, foot - a), n) >= 0.0 &&
                            glm::dot(glm::cross(c - b, foot - b), n) >= 0.0 &&
                            glm::dot(glm::cross(a - c, foot - c), n) >= 0.0;
        if (inside) return glm::length(p - foot);
    }
    return std::min({segmentDistance(p, a, b), segmentDistance(p, b, c), segmentDistance(p, c, a)});
}

/// Unsigned distance from `p` to the nearest triangle of `mesh`, trying every one.
double bruteForceDistance(const MeshData& mesh, const glm::dvec3& p) {
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
        best = std::min(best, triangleDistance(p, glm::dvec3(mesh.positions[mesh.indices[i]]),
                                               glm::dvec3(mesh.positions[mesh.indices[i + 1]]),
                                               glm::dvec3(mesh.positions[mesh.indices[i + 2]])));
    }
    return best;
}

/// Signed distance of an axis-aligned box of half extents `h` centred on the origin.
double boxSdf(const glm::dvec3& p, const glm::dvec3& h) {
    const glm::dvec3 q = glm::abs(p) - h;
    return glm::length(glm::max(q, 0.0)) + std::min(std::max({q.x, q.y, q.z}), 0.0);
}

DistanceField bake(const MeshData& mesh, const DistanceFieldSettings& settings = {}) {
    Result<DistanceField> field = bakeDistanceField(mesh, settings);
    EXPECT_TRUE(field.ok()) << (field.ok() ? "" : field.error().message);
    return field.ok() ? std::move(field).value() : DistanceField{};
}

/// Calls `f(voxel, value)` for every voxel of `field`.
template <typename F>
void forEachVoxel(const DistanceField& field, F&& f) {
    for (int z = 0; z < field.size.z; ++z) {
        for (int y = 0; y < field.size.y; ++y) {
            for (int x = 0; x < field.size.x; ++x) f(glm::ivec3(x, y, z), field.distances[field.index({x, y, z})]);
        }
    }
}

/// The box of makeBoxMesh without its +Y face (the fourth face: -x, +x, -y, +y, -z, +z).
MeshData openTopBox(const glm::vec3& halfExtents) {
    MeshData mesh = *makeBoxMesh(halfExtents);
    mesh.indices.erase(mesh.indices.begin() + 18, mesh.indices.begin() + 24);
    return mesh;
}

// ---- Closed forms ---------------------------------------------------------------------------

TEST(DistanceField, ClosedBoxIsNegativeInsideAndExactEverywhere) {
    const glm::dvec3 half(0.5, 0.3, 0.2);
    const MeshData box = *makeBoxMesh(glm::vec3(half));
    const DistanceField field = bake(box);
    const double tol = kExact * longestExtent(box);
    int inside = 0;
    forEachVoxel(field, [&](const glm::ivec3& v, float value) {
        const double truth = boxSdf(glm::dvec3(field.voxelCentre(v)), half);
        ASSERT_NEAR(value, truth, tol) << "voxel " << v.x << " " << v.y << " " << v.z;
        if (truth < -tol) ++inside;
    });
    EXPECT_GT(inside, 1000);  // the test saw the inside at all
    EXPECT_LT(sampleDistance(field, {0.0f, 0.0f, 0.0f}), -0.19f);
}

TEST(DistanceField, FlippedWindingKeepsTheSign) {
    const MeshData box = *makeBoxMesh(glm::vec3(0.5f, 0.3f, 0.2f));
    MeshData flipped = box;
    for (std::size_t i = 0; i < flipped.indices.size(); i += 3)
        std::swap(flipped.indices[i + 1], flipped.indices[i + 2]);
    const DistanceField a = bake(box);
    const DistanceField b = bake(flipped);
    EXPECT_EQ(a.distances, b.distances);
}

TEST(DistanceField, OpenPlaneIsUnsignedZeroOnItAndExactAbove) {
    const MeshData plane = *makePlaneMesh(1.0f, 4);
    const DistanceFieldSettings settings;
    const DistanceField field = bake(plane, settings);
    const double tol = kExact * longestExtent(plane);
    EXPECT_EQ(field.size.y, 1 + 2 * settings.paddingVoxels);
    forEachVoxel(field, [&](const glm::ivec3& v, float value) {
        const glm::vec3 c = field.voxelCentre(v);
        ASSERT_GE(value, 0.0f) << "voxel " << v.x << " " << v.y << " " << v.z;
        if (std::abs(c.x) <= 1.0f && std::abs(c.z) <= 1.0f) {
            ASSERT_NEAR(value, std::abs(c.y), tol);
        }
    });
    std::mt19937 rng(7);
    // A voxel in from the edges, where the eight centres around a point all lie over the plane.
    std::uniform_real_distribution<float> onPlane(-1.0f + field.voxelSize, 1.0f - field.voxelSize);
    for (int i = 0; i < 200; ++i) {
        const glm::vec3 p(onPlane(rng), 0.0f, onPlane(rng));
        EXPECT_NEAR(sampleDistance(field, p), 0.0f, tol);
        // Above the plane the distance is linear in y: the trilinear sample is exact there.
        const glm::vec3 above(p.x, 1.5f * field.voxelSize, p.z);
        EXPECT_NEAR(sampleDistance(field, above), above.y, tol);
    }
}

// A shell without its top is open: a path from the grid's boundary enters through the opening,
// so the field is unsigned (the rule of distance_field.h), and inside it holds the distance to
// the walls, which a march starting there needs to find the opening.
TEST(DistanceField, BoxWithoutOneFaceIsUnsignedAndExact) {
    const MeshData shell = openTopBox(glm::vec3(0.5f, 0.3f, 0.2f));
    const DistanceField field = bake(shell);
    const double tol = kExact * longestExtent(*makeBoxMesh(glm::vec3(0.5f, 0.3f, 0.2f)));
    forEachVoxel(field, [&](const glm::ivec3& v, float value) {
        ASSERT_GE(value, 0.0f) << "voxel " << v.x << " " << v.y << " " << v.z;
        ASSERT_NEAR(value, bruteForceDistance(shell, glm::dvec3(field.voxelCentre(v))), tol);
    });
    EXPECT_NEAR(sampleDistance(field, {0.0f, 0.0f, 0.0f}), 0.2f, field.voxelSize);
}

TEST(DistanceField, OutsideTheBoxTheSampleIsALowerBound) {
    const glm::dvec3 half(0.5, 0.3, 0.2);
    const DistanceField field = bake(*makeBoxMesh(glm::vec3(half)));
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> far(-6.0f, 6.0f);
    int outside = 0;
    for (int i = 0; i < 2000; ++i) {
        const glm::vec3 p(far(rng), far(rng), far(rng));
        const glm::vec3 toBox = glm::max(glm::max(field.box.min - p, p - field.box.max), glm::vec3(0.0f));
        if (glm::length(toBox) == 0.0f) continue;
        ++outside;
        const float sample = sampleDistance(field, p);
        ASSERT_LE(sample, boxSdf(glm::dvec3(p), half) + 1e-5) << p.x << " " << p.y << " " << p.z;
        ASSERT_GE(sample, glm::length(toBox) * (1.0f - 1e-6f));
    }
    EXPECT_GT(outside, 1000);
}

TEST(DistanceField, SampleOfANonFinitePointIsNaN) {
    const DistanceField field = bake(*makeBoxMesh(glm::vec3(0.5f)));
    EXPECT_TRUE(std::isnan(sampleDistance(field, {std::numeric_limits<float>::quiet_NaN(), 0.0f, 0.0f})));
    EXPECT_TRUE(std::isnan(sampleDistance(field, {0.0f, std::numeric_limits<float>::infinity(), 0.0f})));
}

TEST(DistanceField, SampleOfAFieldWithoutItsVoxelsIsInfinite) {
    DistanceField field = bake(*makeBoxMesh(glm::vec3(0.5f)));
    field.distances.pop_back();
    EXPECT_EQ(sampleDistance(field, {0.0f, 0.0f, 0.0f}), std::numeric_limits<float>::infinity());
    EXPECT_EQ(sampleDistance(DistanceField{}, {0.0f, 0.0f, 0.0f}), std::numeric_limits<float>::infinity());
}

// ---- The bunny ------------------------------------------------------------------------------

class BunnyField : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        Result<std::shared_ptr<MeshData>> mesh = loadObjMesh(kBunnyObjPath);
        if (!mesh.ok()) return;
        bunny_ = *mesh;
        Result<DistanceField> field = bakeDistanceField(*bunny_);
        if (field.ok()) field_ = std::move(field).value();
    }
    static void TearDownTestSuite() { bunny_.reset(); }

    void SetUp() override {
        if (!bunny_) GTEST_SKIP() << kBunnyObjPath << " is missing (Debian package glmark2-data)";
        ASSERT_FALSE(field_.distances.empty()) << "the bunny did not bake";
    }

    static std::shared_ptr<MeshData> bunny_;
    static DistanceField field_;
};

std::shared_ptr<MeshData> BunnyField::bunny_;
DistanceField BunnyField::field_;

// Random voxels, half of them within two voxels of the surface, against every triangle.
TEST_F(BunnyField, VoxelsAreExactAgainstBruteForce) {
    const double tol = kExact * longestExtent(*bunny_);
    std::vector<glm::ivec3> near;
    std::vector<glm::ivec3> all;
    forEachVoxel(field_, [&](const glm::ivec3& v, float value) {
        all.push_back(v);
        if (std::abs(value) < 2.0f * field_.voxelSize) near.push_back(v);
    });
    std::mt19937 rng(11);
    std::shuffle(near.begin(), near.end(), rng);
    std::shuffle(all.begin(), all.end(), rng);
    ASSERT_GT(near.size(), 150u);
    std::vector<glm::ivec3> picked(near.begin(), near.begin() + 150);
    picked.insert(picked.end(), all.begin(), all.begin() + 150);
    for (const glm::ivec3& v : picked) {
        const float value = field_.distances[field_.index(v)];
        const double truth = bruteForceDistance(*bunny_, glm::dvec3(field_.voxelCentre(v)));
        ASSERT_NEAR(std::abs(value), truth, tol) << "voxel " << v.x << " " << v.y << " " << v.z;
    }
}

TEST_F(BunnyField, ClosedBunnyIsNegativeInsideAndPositiveOnTheBoundary) {
    // Every edge of this bunny is shared by two triangles; (0, -0.3, 0) has winding number 1,
    // 0.33 from the nearest vertex.
    EXPECT_LT(sampleDistance(field_, {0.0f, -0.3f, 0.0f}), -0.1f);
    EXPECT_GT(sampleDistance(field_, {0.0f, 0.5f, 0.0f}), 0.0f);  // between the ears: outside
    forEachVoxel(field_, [&](const glm::ivec3& v, float value) {
        const bool boundary = glm::any(glm::equal(v, glm::ivec3(0))) || glm::any(glm::equal(v, field_.size - 1));
        if (boundary) {
            ASSERT_GT(value, 0.0f);
        }
    });
}

// Between centres the sample may exceed the truth by up to half a voxel's diagonal (the bound of
// distance_field.h), never more; beyond the box it is a lower bound.
TEST_F(BunnyField, SampleStaysWithinItsStatedBound) {
    const double tol = kExact * longestExtent(*bunny_);
    const glm::vec3 lo = field_.box.min - field_.box.extent() * 0.5f;
    const glm::vec3 hi = field_.box.max + field_.box.extent() * 0.5f;
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    for (int i = 0; i < 200; ++i) {
        const glm::vec3 p = glm::mix(lo, hi, glm::vec3(u(rng), u(rng), u(rng)));
        const float sample = sampleDistance(field_, p);
        const double truth = bruteForceDistance(*bunny_, glm::dvec3(p));
        const bool inBox =
            glm::all(glm::greaterThanEqual(p, field_.box.min)) && glm::all(glm::lessThanEqual(p, field_.box.max));
        const double slack = inBox ? kHalfDiagonal * field_.voxelSize : 0.0;
        ASSERT_LE(std::abs(sample), truth + slack + tol) << p.x << " " << p.y << " " << p.z;
    }
    for (std::size_t i = 0; i < bunny_->positions.size(); i += 97) {
        EXPECT_LE(std::abs(sampleDistance(field_, bunny_->positions[i])), kHalfDiagonal * field_.voxelSize + tol);
    }
}

// ---- Layout and threads ---------------------------------------------------------------------

TEST(DistanceField, GridFitsTheBudgetWithCubicVoxelsAlongTheLongestAxis) {
    const MeshData box = *makeBoxMesh(glm::vec3(1.0f, 0.5f, 0.25f));
    for (int budget : {kMinDistanceFieldVoxels, 32 * 32 * 32, 64 * 64 * 64}) {
        DistanceFieldSettings settings;
        settings.voxelBudget = budget;
        const DistanceField field = bake(box, settings);
        const std::int64_t voxels = std::int64_t{field.size.x} * field.size.y * field.size.z;
        EXPECT_LE(voxels, budget);
        EXPECT_GT(voxels, budget * 6 / 10) << "the budget is not used";
        EXPECT_GT(field.size.x, field.size.y);
        EXPECT_GT(field.size.y, field.size.z);
        EXPECT_EQ(field.distances.size(), static_cast<std::size_t>(voxels));
        EXPECT_EQ(field.byteSize(), 4u * static_cast<std::size_t>(voxels));
        for (int a = 0; a < 3; ++a) {
            EXPECT_NEAR(field.box.max[a] - field.box.min[a], field.size[a] * field.voxelSize, 1e-5f);
            // The padding: the mesh keeps paddingVoxels of empty space from every face.
            EXPECT_LE(field.box.min[a], box.bounds.min[a] - settings.paddingVoxels * field.voxelSize * 0.999f);
            EXPECT_GE(field.box.max[a], box.bounds.max[a] + settings.paddingVoxels * field.voxelSize * 0.999f);
        }
    }
}

TEST(DistanceField, ThreadCountDoesNotChangeTheField) {
    const MeshData shell = openTopBox(glm::vec3(0.5f, 0.3f, 0.2f));
    DistanceFieldSettings one;
    one.threads = 1;
    DistanceFieldSettings three;
    three.threads = 3;
    EXPECT_EQ(bake(shell, one).distances, bake(shell, three).distances);
}

// ---- Bad input ------------------------------------------------------------------------------

void expectError(const Result<DistanceField>& r, ErrorCode code, const std::string& element) {
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(errorCodeName(r.error().code), std::string(errorCodeName(code))) << r.error().message;
    EXPECT_EQ(r.error().element, element) << r.error().message;
}

TEST(DistanceField, RejectsMeshesWithoutUsableTriangles) {
    MeshData empty;
    expectError(bakeDistanceField(empty), ErrorCode::InvalidValue, "indices");

    MeshData degenerate;
    degenerate.positions = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {1, 1, 1}};
    degenerate.indices = {0, 1, 2, 3, 3, 3};
    expectError(bakeDistanceField(degenerate), ErrorCode::InvalidValue, "indices");

    MeshData ragged = *makeBoxMesh(glm::vec3(1.0f));
    ragged.indices.pop_back();
    expectError(bakeDistanceField(ragged), ErrorCode::InvalidValue, "indices");

    MeshData dangling = *makeBoxMesh(glm::vec3(1.0f));
    dangling.indices[7] = 1000;
    expectError(bakeDistanceField(dangling), ErrorCode::InvalidValue, "indices[7]");
}

TEST(DistanceField, RejectsNonFiniteAndFarPositions) {
    MeshData nan = *makeBoxMesh(glm::vec3(1.0f));
    nan.positions[5].y = std::numeric_limits<float>::quiet_NaN();
    expectError(bakeDistanceField(nan), ErrorCode::InvalidValue, "positions[5]");

    MeshData far = *makeBoxMesh(glm::vec3(1.0f));
    far.positions[2].x = 1e30f;
    expectError(bakeDistanceField(far), ErrorCode::LimitExceeded, "positions[2]");
}

TEST(DistanceField, RejectsSettingsOutOfRange) {
    const MeshData box = *makeBoxMesh(glm::vec3(1.0f));
    DistanceFieldSettings s;
    s.voxelBudget = kMinDistanceFieldVoxels - 1;
    expectError(bakeDistanceField(box, s), ErrorCode::InvalidArgument, "voxelBudget");
    s.voxelBudget = kMaxDistanceFieldVoxels + 1;
    expectError(bakeDistanceField(box, s), ErrorCode::InvalidArgument, "voxelBudget");
    s = {};
    s.paddingVoxels = 0;
    expectError(bakeDistanceField(box, s), ErrorCode::InvalidArgument, "paddingVoxels");
    s = {};
    s.threads = -1;
    expectError(bakeDistanceField(box, s), ErrorCode::InvalidArgument, "threads");
}

}  // namespace
}  // namespace shadow
