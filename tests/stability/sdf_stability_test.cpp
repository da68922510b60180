// The distance-field technique (sdf) through the stability suite's extreme cases: thin plates,
// contact, the scene far from the origin, emitters of size 0 and far beyond any scene, and fields
// the atlas cannot hold. Every frame keeps the frame invariants (`test::expectSaneFrame`: no
// NaN/Inf in any AOV or map, visibility in [0, 1]); every figure is printed as a `[ measured ]`
// line for tests/stability/README.md.
//
// The march (shaders/shadow_sdf.glsl) starts `sdfStartOffset` off the receiver along its normal
// and takes its first sample another `sdfStartOffset` along the ray, and never steps less than
// `sdfMinStep`: a caster whose whole thickness lies nearer the receiver than the first sample is
// passed over, and one thinner than a step may be stepped over.
#include <shadow/context.h>
#include <shadow/distance_field.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "stability/stability_test_support.h"
#include "test_support.h"

namespace shadow::sdf_stability_test {
namespace {

/// One light of a scene, as the checks need it.
struct LightCase {
    const char* name;
    LightType type;
    glm::dvec3 position;
    glm::dvec3 direction;  ///< unit
    [[nodiscard]] test::AnalyticLight analytic() const { return {type, position, direction}; }
    /// Direction (not unit) from `p` towards the light.
    [[nodiscard]] glm::dvec3 towards(const glm::dvec3& p) const {
        return type == LightType::Directional ? -direction : position - p;
    }
};

constexpr float kSpotCone = 0.5f;
/// The contact suite's bound: the ground under a caster's inner part dark (V < 0.5).
constexpr double kMinDarkUnder = 0.99;
/// The grazing-light suite's acne bound: lit ground read dark (V < 0.5).
constexpr double kMaxAcne = 0.001;

LightCase lightAt3m(const char* name, LightType type, const glm::dvec3& direction) {
    const glm::dvec3 d = glm::normalize(direction);
    return {name, type, -3.0 * d, d};
}

/// The contact suite's lights (contact_test.cpp): a sun straight down and at 62 degrees, a tilted
/// spot and a point light, 3 m from the origin.
std::array<LightCase, 4> contactLights() {
    return {lightAt3m("sun straight down", LightType::Directional, {0, -1, 0}),
            lightAt3m("sun at 62 deg", LightType::Directional, {0.5, -1, 0.2}),
            lightAt3m("spot tilted", LightType::Spot, {0.4, -1, -0.3}),
            lightAt3m("point", LightType::Point, {0.3, -1, 0.2})};
}

/// Technique sdf; the map (`mapSize`) holds only casters without a field.
Shadow sdfShadow(int mapSize = 512) { return test::shadowWith(ShadowTechnique::Sdf, mapSize); }

/// Sets every light's emitter: `radius` (m) for spot and point lights, `angularRadius` (rad) for
/// suns (each light type reads one of them).
void setEmitters(Scene& scene, float radius, float angularRadius) {
    scene.world.view<Light>().each([&](Entity, Light& l) {
        l.radius = l.type == LightType::Directional ? 0.0f : radius;
        l.angularRadius = l.type == LightType::Directional ? angularRadius : 0.0f;
    });
}

/// Adds the lights of `lights`, technique sdf, with the contact suite's small emitters (5 cm
/// spot and point, 0.01 rad sun).
template <typename Lights>
void addSdfLights(Scene& scene, const Lights& lights) {
    for (const LightCase& c : lights) {
        addLight(scene, c.name, test::pointSizedLight(c.type, kSpotCone), sdfShadow(), c.position, c.direction);
    }
    setEmitters(scene, 0.05f, 0.01f);
}

void setMarch(Scene& scene, float startOffset, float minStep) {
    scene.world.view<Shadow>().each([&](Entity, Shadow& s) {
        s.sdfStartOffset = startOffset;
        s.sdfMinStep = minStep;
    });
}

/// Renders one frame and checks the frame invariants on it (AOVs and maps); every light draws sdf.
test::RenderedFrame renderSane(FrameRunner& runner, Scene& scene, int width, int height, const std::string& what) {
    const test::RenderedFrame frame = test::renderFrame(runner, scene, width, height);
    test::expectSaneFrame(frame.images, runner.shadows(), what);
    for (const ShadowLightPlan& plan : runner.shadows().frame().lights) {
        EXPECT_EQ(plan.technique(), ShadowTechnique::Sdf) << what << ": " << plan.name;
    }
    return frame;
}

std::string millimetres(float metres) {
    char text[32];
    std::snprintf(text, sizeof text, "%g mm", static_cast<double>(metres) * 1000.0);
    return text;
}

/// Ground pixels of light `index` whose ray to the light crosses the plane y = `height` within
/// |x - centre.x| <= halfX, |z - centre.z| <= halfZ (a caster's footprint, inset).
test::GroundCounts countUnder(const FrameImages& im, std::size_t index, const LightCase& c, const glm::dvec3& centre,
                              double halfX, double halfZ, double height) {
    return test::countGround(im, index, [&](const glm::dvec3& p) {
        const glm::dvec3 to = c.towards(p);
        const glm::dvec3 q = p + to * ((height - p.y) / to.y);
        return std::abs(q.x - centre.x) <= halfX && std::abs(q.z - centre.z) <= halfZ;
    });
}

/// Ground pixels lit by ray casting at `p` and 5 cm around it (beyond every penumbra here),
/// inside a spot's cone; `dark`: of those, visibility < 0.5, `darkened`: < 0.99.
struct LitGround {
    int lit = 0;
    int dark = 0;
    int darkened = 0;
    [[nodiscard]] double darkFraction() const { return lit > 0 ? static_cast<double>(dark) / lit : 0.0; }
    [[nodiscard]] double darkenedFraction() const { return lit > 0 ? static_cast<double>(darkened) / lit : 0.0; }
};

template <typename Boxes>
LitGround litGround(const FrameImages& im, std::size_t index, const LightCase& c, const Boxes& boxes) {
    LitGround g;
    const test::AnalyticLight light = c.analytic();
    for (int y = 0; y < im.position.height; ++y) {
        for (int x = 0; x < im.position.width; ++x) {
            if (!test::isGroundPixel(im, x, y)) continue;
            const glm::dvec3 p = test::positionAt(im, x, y);
            if (c.type == LightType::Spot && !test::insideCone(p, c.position, c.direction, kSpotCone - 0.05)) continue;
            bool lit = test::analyticallyLit(light, p, boxes);
            for (int k = 0; k < 8 && lit; ++k) {
                const double a = k * 0.25 * test::kPi;
                lit = test::analyticallyLit(light, p + 0.05 * glm::dvec3(std::cos(a), 0.0, std::sin(a)), boxes);
            }
            if (!lit) continue;
            ++g.lit;
            const float v = im.visibility[index].at(x, y, 0);
            g.dark += v < 0.5f ? 1 : 0;
            g.darkened += v < 0.99f ? 1 : 0;
        }
    }
    return g;
}

// ---------------------------------------------------------------------------------------------
// 1. Thin plates (closed boxes) 20 cm over the ground, far beyond any start offset: the plate is
// the caster, the ground the receiver.

constexpr double kPlateHalf = 0.3;
constexpr double kPlateBottom = 0.2;

/// The fraction of the ground dark under the inner part of a plate `thickness` thick (5 cm
/// inside its edges), per light of `contactLights`, with the march's shortest step `minStep`.
std::array<double, 4> darkUnderPlate(double thickness, float minStep, const std::string& what) {
    const glm::dvec3 centre{0.0, kPlateBottom + 0.5 * thickness, 0.0};
    Scene scene;
    test::addGround(scene, 1.3f);
    test::addBox(scene, "plate", centre, {kPlateHalf, 0.5 * thickness, kPlateHalf});
    const std::array<LightCase, 4> lights = contactLights();
    addSdfLights(scene, lights);
    setMarch(scene, Shadow{}.sdfStartOffset, minStep);
    // The plate hides the ground under it from above; the ground is open and two-sided.
    addCamera(scene, "camera", Camera{}, {0.0, -2.0, 0.3}, {0.0, 0.0, 0.0});
    test::glContext();
    FrameRunner runner;
    const test::RenderedFrame frame = renderSane(runner, scene, 192, 192, what);
    std::array<double, 4> dark{};
    for (std::size_t i = 0; i < lights.size(); ++i) {
        const test::GroundCounts under =
            countUnder(frame.images, i, lights[i], centre, kPlateHalf - 0.05, kPlateHalf - 0.05, centre.y);
        test::reportFigure("sdf, " + what + ", " + lights[i].name + ": dark fraction under the plate",
                           under.darkFraction());
        EXPECT_GT(under.ground, 1000) << what << ", " << lights[i].name;
        dark[i] = under.darkFraction();
    }
    return dark;
}

// Plates 1 cm and 1 mm thick with the default march, and the 1 mm plate with a shortest step of
// half its thickness (0.5 mm), under every light: the whole shadow. The 1 mm plate is the hard
// one: near it the march steps sdfMinStep (5 mm) along the ray, which crosses the plate (2.2 mm
// of ray at 62 degrees) between two samples, both outside it, and its 1 cm voxels give it no
// inside wider than itself. Measured on the work in progress of 30243e7, before its check for
// thin casters crossed at a slant: 100 % dark under the sun straight down but 0 under the sun at
// 62 deg (visibility 0.67), 13-23 % under the tilted spot and 0-20 % under the point light; with
// that check, and with sdfMinStep 0.5 mm before it, 100 %.
TEST(Stability, SdfThinPlatesOverTheGroundCastTheirShadow) {
    const std::array<LightCase, 4> lights = contactLights();
    const std::array<double, 4> cm = darkUnderPlate(0.01, Shadow{}.sdfMinStep, "1 cm plate 20 cm up");
    const std::array<double, 4> mm = darkUnderPlate(0.001, Shadow{}.sdfMinStep, "1 mm plate 20 cm up");
    const std::array<double, 4> mmFine = darkUnderPlate(0.001, 0.0005f, "1 mm plate 20 cm up, sdfMinStep 0.5 mm");
    for (std::size_t i = 0; i < lights.size(); ++i) {
        EXPECT_GE(cm[i], kMinDarkUnder) << "1 cm plate, " << lights[i].name << ": light leak";
        EXPECT_GE(mm[i], kMinDarkUnder) << "1 mm plate, " << lights[i].name << ": light leak (stepped over)";
        EXPECT_GE(mmFine[i], kMinDarkUnder) << "1 mm plate, sdfMinStep 0.5 mm, " << lights[i].name << ": light leak";
    }
}

// ---------------------------------------------------------------------------------------------
// 2. Contact: casters 1 cm above the ground, a slab 1 cm thick and a box 20 cm tall. The first
// sample lies about 2 x sdfStartOffset off the ground (along the normal, then along the ray):
// with an offset of 2 cm it lies above the slab (its contact missed: reported, not bounded) but
// inside the box. Any offset up to half the gap must see both; and no offset may darken the lit
// ground (acne).

TEST(Stability, SdfCasterOneCentimetreAboveTheGroundNeedsASmallerStartOffset) {
    constexpr double kGap = 0.01;
    struct Caster {
        const char* name;
        glm::dvec3 centre;
        glm::dvec3 half;
    };
    const std::array<Caster, 2> casters{{{"slab 1 cm thick", {-0.4, kGap + 0.005, 0.0}, {0.3, 0.005, 0.3}},
                                         {"box 20 cm tall", {0.4, kGap + 0.1, 0.0}, {0.3, 0.1, 0.3}}}};
    Scene scene;
    test::addGround(scene, 1.3f);
    std::vector<DAabb> boxes;
    for (const Caster& c : casters) {
        test::addBox(scene, c.name, c.centre, c.half);
        boxes.push_back(test::boxBounds(c.centre, c.half));
    }
    const std::array<LightCase, 4> lights = contactLights();
    addSdfLights(scene, lights);
    addCamera(scene, "camera", Camera{}, {0.0, -2.6, 0.3}, {0.0, 0.0, 0.0});  // from below
    test::glContext();
    FrameRunner runner;
    // 2 cm, the default, and 5 mm: every offset up to half the gap must see the contact.
    for (float offset : {0.02f, Shadow{}.sdfStartOffset, 0.005f}) {
        setMarch(scene, offset, Shadow{}.sdfMinStep);
        const std::string setting = "start offset " + millimetres(offset);
        const test::RenderedFrame frame = renderSane(runner, scene, 192, 192, "contact, " + setting);
        const bool mustSeeContact = offset <= 0.5 * kGap;
        for (std::size_t i = 0; i < lights.size(); ++i) {
            for (const Caster& c : casters) {
                // Under the caster's bottom face, 5 cm inside its edges.
                const test::GroundCounts under = countUnder(frame.images, i, lights[i], c.centre, c.half.x - 0.05,
                                                            c.half.z - 0.05, c.centre.y - c.half.y);
                const std::string name =
                    std::string(c.name) + " 1 cm above the ground, " + lights[i].name + ", " + setting;
                test::reportFigure("sdf, " + name + ": dark fraction under it", under.darkFraction());
                EXPECT_GT(under.ground, 1000) << name;
                if (mustSeeContact) {
                    EXPECT_GE(under.darkFraction(), kMinDarkUnder) << name << ": contact missed";
                }
            }
            const LitGround lit = litGround(frame.images, i, lights[i], boxes);
            const std::string name = std::string(lights[i].name) + ", " + setting;
            test::reportFigure("sdf, contact, " + name + ": lit ground read dark (V < 0.5)", lit.darkFraction());
            test::reportFigure("sdf, contact, " + name + ": lit ground darkened (V < 0.99)", lit.darkenedFraction());
            EXPECT_GT(lit.lit, 2000) << name;
            EXPECT_LT(lit.darkFraction(), kMaxAcne) << name << ": acne";
        }
    }
}

// ---------------------------------------------------------------------------------------------
// 3. The far-from-origin suite's scene (far_from_origin_test.cpp), its three lights at once,
// point-sized, translated by 10^4 m and 10^5 m.

const glm::dvec3 kFarBoxCentre{0.0, 1.4, 0.0};
const glm::dvec3 kFarBoxHalf{0.8, 0.4, 0.6};

std::array<LightCase, 3> farLights() {
    return {LightCase{"sun", LightType::Directional, {0, 10, 0}, glm::normalize(glm::dvec3(0.6, -1.0, 0.35))},
            LightCase{
                "spot", LightType::Spot, {-2.5, 4.0, 1.0}, glm::normalize(kFarBoxCentre - glm::dvec3(-2.5, 4.0, 1.0))},
            LightCase{"point", LightType::Point, {0.7, 3.5, -0.4}, {0, -1, 0}}};
}

/// Per light: the visibility image and the ground's mismatch against ray casting (all of it, and
/// beyond two voxels of the box's field: a field places an edge to within about a voxel).
struct FarResult {
    std::vector<std::vector<float>> visibility;
    std::vector<double> mismatch;
    std::vector<double> beyondBand;
};

FarResult renderFar(const glm::dvec3& origin, double voxel) {
    Scene scene;
    addMeshInstance(scene.world, "ground", makePlaneMesh(6.0f, 4), test::placed(origin));
    test::addBox(scene, "box", origin + kFarBoxCentre, kFarBoxHalf);
    std::array<LightCase, 3> lights = farLights();
    for (LightCase& c : lights) {
        c.position += origin;
        addLight(scene, c.name, test::pointSizedLight(c.type, 0.6f), sdfShadow(1024), c.position, c.direction);
    }
    addCamera(scene, "camera", Camera{}, origin + glm::dvec3(0.3, 4.0, 4.8), origin + glm::dvec3(0.3, 0.0, 0.3));
    const std::array<DAabb, 1> boxes{test::boxBounds(origin + kFarBoxCentre, kFarBoxHalf)};
    test::glContext();
    FrameRunner runner;
    const test::RenderedFrame frame =
        renderSane(runner, scene, 192, 144, "far from the origin, x = " + std::to_string(static_cast<long>(origin.x)));
    FarResult r;
    for (std::size_t i = 0; i < lights.size(); ++i) {
        const ShadowLightPlan& plan = runner.shadows().frame().lights.at(i);
        const test::AnalyticLight light = lights[i].analytic();
        const double band = 2.0 * voxel / test::groundTexelAt(plan, light, origin);
        const test::GeometryAgreement m =
            test::compareWithGeometry(frame.images, frame.images.visibility[i], plan, light, boxes, band, 0.6);
        EXPECT_GT(m.shadowedPixels, m.groundPixels / 50) << lights[i].name << ": shadow out of view";
        r.mismatch.push_back(static_cast<double>(m.mismatches) / std::max(m.groundPixels, 1));
        r.beyondBand.push_back(static_cast<double>(m.outsideBand) / std::max(m.groundPixels, 1));
        r.visibility.push_back(frame.images.visibility[i].pixels);
    }
    return r;
}

TEST(Stability, SdfTranslatedSceneMatchesTheOriginScene) {
    // The box's field as the atlas bakes it (64^3 voxels over its longest side).
    const Result<DistanceField> field = bakeDistanceField(*makeBoxMesh(glm::vec3(kFarBoxHalf)));
    ASSERT_TRUE(field.ok());
    const double voxel = field->voxelSize;
    const FarResult atOrigin = renderFar(glm::dvec3(0.0), voxel);
    const std::array<LightCase, 3> lights = farLights();
    for (double offset : {1e4, 1e5}) {
        // Along both horizontal axes; the ground stays at y = 0, where the checks find it.
        const FarResult far = renderFar(glm::dvec3(offset, 0.0, -0.73 * offset), voxel);
        for (std::size_t i = 0; i < lights.size(); ++i) {
            const std::string name =
                std::string("sdf, ") + lights[i].name + " at " + std::to_string(static_cast<long>(offset)) + " m";
            int flipped = 0;
            for (std::size_t p = 0; p < far.visibility[i].size(); ++p) {
                flipped += (far.visibility[i][p] > 0.5f) != (atOrigin.visibility[i][p] > 0.5f) ? 1 : 0;
            }
            const double flippedFraction = static_cast<double>(flipped) / static_cast<double>(far.visibility[i].size());
            test::reportFigure(name + ": pixels flipped against the origin image", flippedFraction);
            test::reportFigure(name + ": ground disagreeing with ray casting (origin " +
                                   std::to_string(atOrigin.mismatch[i]).substr(0, 7) + ")",
                               far.mismatch[i]);
            test::reportFigure(
                name + ": beyond two voxels (origin " + std::to_string(atOrigin.beyondBand[i]).substr(0, 7) + ")",
                far.beyondBand[i]);
            // The far-from-origin suite's bounds: 0.1 % of the pixels flipped, nothing more
            // beyond the band than at the origin (give or take 0.01 % of the ground).
            EXPECT_LE(flippedFraction, 0.001) << name;
            EXPECT_LE(far.beyondBand[i], atOrigin.beyondBand[i] + 1e-4) << name;
        }
    }
}

// ---------------------------------------------------------------------------------------------
// 4. Emitters of size 0 (the hard shadow) and far beyond the scene (finite, clamped).

const glm::dvec3 kBoxCentre{0.3, 0.6, -0.2};
const glm::dvec3 kBoxHalf{0.4, 0.3, 0.5};

std::array<LightCase, 3> emitterLights() {
    return {
        LightCase{"sun", LightType::Directional, {0, 10, 0}, glm::normalize(glm::dvec3(0.4, -1.0, 0.3))},
        LightCase{"spot", LightType::Spot, {-1.5, 4.0, 1.0}, glm::normalize(kBoxCentre - glm::dvec3(-1.5, 4.0, 1.0))},
        LightCase{"point", LightType::Point, {1.2, 3.0, 0.8}, {0, -1, 0}}};
}

/// Ground pixels of light `index` with visibility < 0.05.
int groundUmbra(const FrameImages& im, std::size_t index) {
    int n = 0;
    const ImageF& v = im.visibility[index];
    for (int y = 0; y < v.height; ++y) {
        for (int x = 0; x < v.width; ++x) n += test::isGroundPixel(im, x, y) && v.at(x, y, 0) < 0.05f ? 1 : 0;
    }
    return n;
}

TEST(Stability, SdfEmitterOfSizeZeroIsHardAndHugeEmittersStayFinite) {
    // sdf_test's scene (DistanceFieldShadows.APointSizedEmitterCastsTheGeometricShadow), its
    // three lights at once.
    Scene scene;
    test::addGround(scene, 4.0f);
    test::addBox(scene, "box", kBoxCentre, kBoxHalf);
    const std::array<LightCase, 3> lights = emitterLights();
    for (const LightCase& c : lights) {
        addLight(scene, c.name, test::pointSizedLight(c.type, 0.7f), sdfShadow(1024), c.position, c.direction);
    }
    addCamera(scene, "camera", Camera{}, {0.0, 4.5, 5.5}, {0.0, 0.0, 0.0});
    const std::array<DAabb, 1> boxes{test::boxBounds(kBoxCentre, kBoxHalf)};
    const Result<DistanceField> field = bakeDistanceField(*makeBoxMesh(glm::vec3(kBoxHalf)));
    ASSERT_TRUE(field.ok());
    const double voxel = field->voxelSize;
    test::glContext();
    FrameRunner runner;

    // Size 0 (radius 0, angularRadius 0): the geometric shadow beyond two voxels of the edge
    // (sdf_test's bound), and no penumbra.
    const test::RenderedFrame hard = renderSane(runner, scene, 192, 144, "emitter 0");
    EXPECT_TRUE(hard.stats.warnings.empty()) << test::describe(hard.stats.warnings);
    std::vector<int> hardDark;
    for (std::size_t i = 0; i < lights.size(); ++i) {
        const ShadowLightPlan& plan = runner.shadows().frame().lights.at(i);
        const test::AnalyticLight light = lights[i].analytic();
        const double band = 2.0 * voxel / test::groundTexelAt(plan, light, glm::dvec3(kBoxCentre.x, 0.0, kBoxCentre.z));
        const test::GeometryAgreement m =
            test::compareWithGeometry(hard.images, hard.images.visibility[i], plan, light, boxes, band, 0.7);
        const std::string name = std::string("sdf, emitter 0, ") + lights[i].name;
        const double ground = std::max(m.groundPixels, 1);
        const test::GroundCounts c = test::countGround(hard.images, i);
        test::reportFigure(name + ": ground disagreeing with ray casting", m.mismatches / ground);
        test::reportFigure(name + ": beyond two voxels", m.outsideBand / ground);
        test::reportFigure(name + ": ground in penumbra (0.05 < V < 0.95)", c.penumbraFraction());
        EXPECT_GT(m.shadowedPixels, m.groundPixels / 100) << name << ": no shadow in view";
        EXPECT_LT(m.outsideBand / ground, 0.001) << name;
        EXPECT_LE(c.penumbraFraction(), 0.001) << name << ": a penumbra without an emitter";
        hardDark.push_back(c.dark);
    }

    // Huge: 100 m and 1000 m (the radius's clamp) for the spot and the point light, 0.1 and
    // 0.2 rad (the angular radius's clamp) for the sun; then 1e9 m and 10 rad, beyond the clamps:
    // clamped with a warning, the clamp's image bit for bit. Reported, not bounded: the ground
    // far from the box reads 0.50-0.52 under the huge spot and point light (their cones, tan e =
    // 25-330, meet the box from everywhere, and the straight-edge model lets its nearest edge
    // cover half the emitter; with the ground casting nothing, the same), 1 under the sun.
    struct Huge {
        const char* name;
        float radius;
        float angularRadius;
    };
    const std::array<Huge, 3> huge{{{"100 m / 0.1 rad", 100.0f, 0.1f},
                                    {"1000 m / 0.2 rad (the clamps)", 1000.0f, 0.2f},
                                    {"1e9 m / 10 rad (beyond the clamps)", 1e9f, 10.0f}}};
    std::vector<std::vector<float>> atClamp;
    std::vector<int> umbraBefore = hardDark;
    for (const Huge& h : huge) {
        setEmitters(scene, h.radius, h.angularRadius);
        const test::RenderedFrame frame = renderSane(runner, scene, 192, 144, std::string("emitter ") + h.name);
        const bool beyond = h.radius > 1000.0f;
        for (std::size_t i = 0; i < lights.size(); ++i) {
            const std::string name = std::string("sdf, emitter ") + h.name + ", " + lights[i].name;
            const ImageF& v = frame.images.visibility[i];
            // The ground 2.5 m and more from the box, inside a spot's cone: no shadow reaches it.
            double farSum = 0.0;
            int farCount = 0;
            for (int y = 0; y < v.height; ++y) {
                for (int x = 0; x < v.width; ++x) {
                    if (!test::isGroundPixel(frame.images, x, y)) continue;
                    const glm::dvec3 p = test::positionAt(frame.images, x, y);
                    if (glm::length(glm::dvec2(p.x - kBoxCentre.x, p.z - kBoxCentre.z)) < 2.5) continue;
                    if (lights[i].type == LightType::Spot &&
                        !test::insideCone(p, lights[i].position, lights[i].direction, 0.6)) {
                        continue;
                    }
                    farSum += v.at(x, y, 0);
                    ++farCount;
                }
            }
            const int umbra = groundUmbra(frame.images, i);
            test::reportFigure(name + ": dark ground (V < 0.5)", test::countGround(frame.images, i).darkFraction());
            test::reportFigure(
                name + ": umbra on the ground (V < 0.05, pixels; hard shadow " + std::to_string(hardDark[i]) + ")",
                umbra);
            test::reportFigure(name + ": mean visibility of the ground 2.5 m from the box",
                               farCount > 0 ? farSum / farCount : -1.0);
            EXPECT_EQ(test::countNonFinite(v), 0) << name;
            EXPECT_GT(farCount, 500) << name;
            // A larger emitter never widens the umbra.
            EXPECT_LE(umbra, umbraBefore[i]) << name << ": the umbra grew with the emitter";
            umbraBefore[i] = umbra;
        }
        if (beyond) {
            for (const LightCase& c : lights) {
                EXPECT_EQ(test::countWarnings(frame.stats.warnings, WarningCode::SettingClamped, c.name), 1)
                    << test::describe(frame.stats.warnings);
            }
            for (std::size_t i = 0; i < lights.size(); ++i) {
                EXPECT_EQ(frame.images.visibility[i].pixels, atClamp[i]) << lights[i].name << ": not the clamp's image";
            }
        } else {
            EXPECT_TRUE(frame.stats.warnings.empty()) << test::describe(frame.stats.warnings);
            atClamp.clear();
            for (const ImageF& v : frame.images.visibility) atClamp.push_back(v.pixels);
        }
    }
}

// ---------------------------------------------------------------------------------------------
// 6. Fields that do not fit. The atlas (engine/src/shadow/distance_field_atlas.cpp, brickOf)
// bakes each mesh once, with an eighth of the voxels while the field is wider than 128 texels in
// x or y (the atlas's edge) or deeper than GL_MAX_3D_TEXTURE_SIZE, down to 16^3; a field that
// fails to bake or still does not fit is warned about once (`CasterWithoutField`, naming the
// light and the mesh) and that caster casts no shadow: it is neither marched nor in the map.

/// GL_MAX_3D_TEXTURE_SIZE of the test context: the atlas's largest depth.
int max3dTextureSize() {
    using GetIntegerv = void (*)(unsigned int, int*);
    constexpr unsigned int kGlMax3dTextureSize = 0x8073u;
    auto get = reinterpret_cast<GetIntegerv>(test::glContext().loader()("glGetIntegerv"));
    int value = 0;
    if (get != nullptr) get(kGlMax3dTextureSize, &value);
    return value;
}

/// A sun straight down (point-sized, technique `technique`) over a ground at y = 0 seen from
/// below; the ground casts nothing unless `groundCasts`.
Scene sunFromBelow(ShadowTechnique technique, bool groundCasts) {
    Scene scene;
    const Entity ground = test::addGround(scene, 1.3f);
    scene.world.get<Mesh>(ground).castShadows = groundCasts;
    addLight(scene, "sun", test::pointSizedLight(LightType::Directional), test::shadowWith(technique, 512), {0, 10, 0},
             {0, -1, 0});
    addCamera(scene, "camera", Camera{}, {0.0, -2.6, 0.3}, {0.0, 0.0, 0.0});
    return scene;
}

/// The fraction of the ground dark (V < 0.5) straight under |x - c.x| <= halfX, |z - c.z| <= halfZ.
double darkUnder(const FrameImages& im, const glm::dvec3& c, double halfX, double halfZ) {
    return test::countGround(
               im, 0, [&](const glm::dvec3& p) { return std::abs(p.x - c.x) <= halfX && std::abs(p.z - c.z) <= halfZ; })
        .darkFraction();
}

/// The `CasterWithoutField` warnings of `warnings` whose message contains `text`.
long fieldWarnings(const std::vector<Warning>& warnings, const std::string& text) {
    return std::count_if(warnings.begin(), warnings.end(), [&](const Warning& w) {
        return w.code == WarningCode::CasterWithoutField && w.element == "sun" &&
               w.message.find(text) != std::string::npos;
    });
}

const glm::vec3 kRodHalf(4.0f, 0.02f, 0.02f);  // 8 m x 4 cm x 4 cm, along x
const glm::vec3 kGiantHalf(2e9f);              // beyond the bake's +-1e9
constexpr double kGiantScale = 1e-10;          // 0.4 m in the world
const glm::dvec3 kRodCentre{0.0, 0.5, -0.5};
const glm::dvec3 kGiantCentre{-0.5, 0.5, 0.3};
const glm::dvec3 kCubeCentre{0.5, 0.5, 0.3};

void addUnfitCasters(Scene& scene) {
    addMeshInstance(scene.world, "rod", makeBoxMesh(kRodHalf), test::placed(kRodCentre));
    addMeshInstance(scene.world, "giant", makeBoxMesh(kGiantHalf), test::placed(kGiantCentre, glm::dvec3(kGiantScale)));
    test::addBox(scene, "cube", kCubeCentre, glm::dvec3(0.2));
}

// A rod whose field is wider than the atlas even at 16^3 voxels, and a box authored at 2e9 units
// (placed at a scale of 1e-10: 0.4 m) whose bake refuses its positions: each warned once, the
// frame sane, the cube beside them casting its shadow. Neither casts (as the warning says);
// technique hard casts both.
TEST(Stability, SdfCasterWhoseFieldCannotBeBakedOrHeldIsReported) {
    DistanceFieldSettings smallest;
    smallest.voxelBudget = kMinDistanceFieldVoxels;
    const Result<DistanceField> rodField = bakeDistanceField(*makeBoxMesh(kRodHalf), smallest);
    ASSERT_TRUE(rodField.ok());
    test::reportFigure("sdf, rod 8 m x 4 cm: its field's width at 16^3 voxels (the atlas holds 128)", rodField->size.x);
    ASSERT_GT(rodField->size.x, 128);
    ASSERT_FALSE(bakeDistanceField(*makeBoxMesh(kGiantHalf)).ok());

    Scene scene = sunFromBelow(ShadowTechnique::Sdf, true);
    addUnfitCasters(scene);
    test::glContext();
    FrameRunner runner;
    const test::RenderedFrame frame = renderSane(runner, scene, 192, 192, "fields that do not fit");
    const std::vector<Warning>& w = frame.stats.warnings;
    EXPECT_EQ(test::countWarnings(w, WarningCode::CasterWithoutField, "sun"), 2) << test::describe(w);
    EXPECT_EQ(fieldWarnings(w, "does not fit the atlas"), 1) << test::describe(w);
    EXPECT_EQ(fieldWarnings(w, "lies beyond"), 1) << test::describe(w);
    EXPECT_EQ(w.size(), 2u) << test::describe(w);
    const double rod = darkUnder(frame.images, kRodCentre, 0.9, 0.01);
    const double giant = darkUnder(frame.images, kGiantCentre, 0.15, 0.15);
    const double cube = darkUnder(frame.images, kCubeCentre, 0.15, 0.15);
    test::reportFigure("sdf, rod wider than the atlas: dark fraction under it", rod);
    test::reportFigure("sdf, box at 2e9 units (bake refused): dark fraction under it", giant);
    test::reportFigure("sdf, cube beside them: dark fraction under it", cube);
    EXPECT_GE(cube, kMinDarkUnder);
    EXPECT_LE(rod, 0.01) << "the rod casts, but the warning says it casts no shadow";
    EXPECT_LE(giant, 0.01) << "the giant casts, but the warning says it casts no shadow";
    // Warned once: the next frame keeps the failed entries without baking or warning again.
    const test::RenderedFrame second = renderSane(runner, scene, 192, 192, "fields that do not fit, second frame");
    EXPECT_TRUE(second.stats.warnings.empty()) << test::describe(second.stats.warnings);
    EXPECT_EQ(second.stats.distanceFieldsBaked, 0);

    Scene hardScene = sunFromBelow(ShadowTechnique::Hard, true);
    addUnfitCasters(hardScene);
    FrameRunner hardRunner;
    const test::RenderedFrame h = test::renderFrame(hardRunner, hardScene, 192, 192);
    test::reportFigure("hard, rod: dark fraction under it", darkUnder(h.images, kRodCentre, 0.9, 0.01));
    test::reportFigure("hard, box at 2e9 units: dark fraction under it", darkUnder(h.images, kGiantCentre, 0.15, 0.15));
}

// An atlas filled up: boxes 1 x 1 x 0.9, whose fields are more than 64 voxels across x and y
// (one per slab of the 128 x 128 atlas), until their slabs exceed GL_MAX_3D_TEXTURE_SIZE. Every
// field that fits casts, each one beyond is warned about and casts nothing. Slow tier: 36
// fields baked, 128 MiB of atlas; the fast tier keeps the warning of a field that does not fit
// (the rod above) and the depth check (the two rods below).
TEST(Stability, SlowSdfAtlasFilledUpReportsTheFieldsBeyondIt) {
    const int depth = max3dTextureSize();
    const glm::vec3 half(0.1f, 0.1f, 0.09f);
    const Result<DistanceField> field = bakeDistanceField(*makeBoxMesh(half));
    ASSERT_TRUE(field.ok());
    ASSERT_GT(field->size.x, 64);
    ASSERT_GT(field->size.y, 64);
    const int fit = depth / field->size.z;
    const int count = fit + 2;
    if (count > 64) GTEST_SKIP() << "an atlas " << depth << " deep takes " << count << " fields to fill";
    Scene scene = sunFromBelow(ShadowTechnique::Sdf, false);
    std::vector<glm::dvec3> centres;
    const int side = static_cast<int>(std::ceil(std::sqrt(count)));
    for (int k = 0; k < count; ++k) {
        const glm::dvec3 c{-1.0 + 2.0 * ((k % side) + 0.5) / side, 0.5, -1.0 + 2.0 * ((k / side) + 0.5) / side};
        addMeshInstance(scene.world, "box " + std::to_string(k), makeBoxMesh(half), test::placed(c));
        centres.push_back(c);
    }
    test::glContext();
    FrameRunner runner;
    const test::RenderedFrame frame = renderSane(runner, scene, 192, 192, "atlas filled up");
    const std::vector<Warning>& w = frame.stats.warnings;
    int casting = 0;
    int notCasting = 0;
    for (const glm::dvec3& c : centres) {
        const double dark = darkUnder(frame.images, c, 0.07, 0.07);
        casting += dark >= kMinDarkUnder ? 1 : 0;
        notCasting += dark <= 0.01 ? 1 : 0;
    }
    test::reportFigure("sdf, atlas " + std::to_string(depth) + " deep, " + std::to_string(count) + " fields of " +
                           std::to_string(field->size.x) + "x" + std::to_string(field->size.y) + "x" +
                           std::to_string(field->size.z) + ": warned",
                       fieldWarnings(w, "does not fit the atlas"));
    test::reportFigure("sdf, atlas filled up: casters casting", casting);
    test::reportFigure("sdf, atlas filled up: atlas MiB", frame.stats.distanceFieldBytes / 1048576.0);
    test::reportFigure("sdf, atlas filled up: bake ms", frame.stats.distanceFieldBakeMs);
    EXPECT_EQ(fieldWarnings(w, "does not fit the atlas"), count - fit) << test::describe(w);
    EXPECT_EQ(w.size(), static_cast<std::size_t>(count - fit)) << test::describe(w);
    EXPECT_EQ(casting, fit);
    EXPECT_EQ(notCasting, count - fit);
}

// Two rods along z whose fields (15 x 15 x 1104 voxels) each take more than half the atlas's
// depth: the second fits beside the first (the atlas is 128 texels wide and `place` puts it at
// x = 15 of the same slab), so both must cast. Fails today: brickOf's fit check counts
// `cursor.z + slabDepth + size.z`, the depth of a new slab, even when the brick goes into the
// current one, and warns "does not fit the atlas".
TEST(Stability, SdfFieldThatFitsBesideAnotherIsHeld) {
    const int depth = max3dTextureSize();
    const glm::vec3 rodHalf(0.05f, 0.05f, 5.0f);
    const Result<DistanceField> field = bakeDistanceField(*makeBoxMesh(rodHalf));
    ASSERT_TRUE(field.ok());
    if (2 * field->size.z <= depth || field->size.z > depth) {
        GTEST_SKIP() << "the case needs a field deeper than half of GL_MAX_3D_TEXTURE_SIZE " << depth;
    }
    ASSERT_LE(2 * field->size.x, 128);
    Scene scene = sunFromBelow(ShadowTechnique::Sdf, false);
    const glm::dvec3 a{-0.3, 0.5, 0.0};
    const glm::dvec3 b{0.3, 0.5, 0.0};
    addMeshInstance(scene.world, "rod a", makeBoxMesh(rodHalf), test::placed(a));
    addMeshInstance(scene.world, "rod b", makeBoxMesh(rodHalf), test::placed(b));
    test::glContext();
    FrameRunner runner;
    const test::RenderedFrame frame = renderSane(runner, scene, 192, 192, "two rods along z");
    const double darkA = darkUnder(frame.images, a, 0.02, 0.8);
    const double darkB = darkUnder(frame.images, b, 0.02, 0.8);
    test::reportFigure("sdf, two z rods of " + std::to_string(field->size.z) + " voxels: dark under the first", darkA);
    test::reportFigure("sdf, two z rods: dark under the second", darkB);
    EXPECT_TRUE(frame.stats.warnings.empty()) << test::describe(frame.stats.warnings);
    EXPECT_GE(darkA, kMinDarkUnder);
    EXPECT_GE(darkB, kMinDarkUnder) << "the second field fits beside the first but was refused";
}

}  // namespace
}  // namespace shadow::sdf_stability_test
