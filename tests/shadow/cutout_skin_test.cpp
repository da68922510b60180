// glTF materials and skins in the shadow passes, against the ray-traced reference (which poses
// skins on the CPU and ignores hits in alpha holes, reference/ray_scene.cpp):
// - a cut-out quad with a checkerboard alpha over a plane casts a checkerboard shadow, with every
//   technique and light type (the distance-field technique casts it through its map);
// - a skinned bar's shadow follows its pose, and its layers are redrawn when, and only when, a
//   joint moved.
#include <gtest/gtest.h>
#include <shadow/reference.h>

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <string>
#include <vector>

#include "render/render_test_support.h"
#include "shadow/truth_test_support.h"

namespace shadow::test::cutout_skin_test {
namespace {

constexpr int kWidth = 240;
constexpr int kHeight = 180;

/// A 64x64 texture whose alpha is a 4x4 checkerboard (opaque cells where (i + j) is even).
std::shared_ptr<const Texture> checkerAlpha() {
    auto t = std::make_shared<Texture>();
    t->name = "checker";
    t->width = 64;
    t->height = 64;
    t->rgba.resize(64 * 64 * 4);
    for (int y = 0; y < 64; ++y) {
        for (int x = 0; x < 64; ++x) {
            const std::size_t i = (static_cast<std::size_t>(y) * 64 + static_cast<std::size_t>(x)) * 4;
            t->rgba[i] = 200;
            t->rgba[i + 1] = 120;
            t->rgba[i + 2] = 60;
            t->rgba[i + 3] = ((x / 16 + y / 16) % 2 == 0) ? 255 : 0;
        }
    }
    t->wrapS = Texture::Wrap::ClampToEdge;
    t->wrapT = Texture::Wrap::ClampToEdge;
    return t;
}

/// A horizontal square of half size `h` in the XZ plane, texture coordinates over [0, 1]^2.
std::shared_ptr<MeshData> texturedQuad(float h) {
    auto m = std::make_shared<MeshData>();
    m->name = "quad";
    m->positions = {{-h, 0, -h}, {h, 0, -h}, {h, 0, h}, {-h, 0, h}};
    m->normals.assign(4, glm::vec3(0, 1, 0));
    m->texcoords = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    m->indices = {0, 2, 1, 0, 3, 2};
    computeBounds(*m);
    return m;
}

/// Ground, a cut-out checker quad 1 m above it, one light of `type` with `technique`, a camera
/// looking down.
Scene cutoutScene(LightType type, ShadowTechnique technique) {
    Scene scene;
    addGround(scene, 3.0f);
    Material cut;
    cut.baseColorTexture = checkerAlpha();
    cut.alphaMode = AlphaMode::Mask;
    cut.alphaCutoff = 0.5f;
    addMeshInstance(scene.world, "checker", texturedQuad(0.8f), placed({0.0, 1.0, 0.0}), cut);
    Light light = pointSizedLight(type, 0.9f);
    Shadow shadow;
    shadow.technique = technique;
    shadow.mapSize = 1024;
    addLight(scene, "light", light, shadow, {0.2, 4.0, 0.1}, glm::normalize(glm::dvec3(-0.05, -1.0, -0.03)));
    addCamera(scene, "camera", Camera{}, {0.0, 4.5, 2.0}, {0.0, 0.0, 0.0});
    return scene;
}

/// The engine's visibility of light 0 against the reference's, over the ground pixels the
/// reference shades.
struct Agreement {
    int pixels = 0;        ///< ground pixels in the quad's shadow footprint (reference < 0.5 within 3 px)
    int mismatches = 0;    ///< of those, where the engine's and the reference's sides of 0.5 differ
    double holeMean = 0;   ///< engine's mean visibility where the reference is lit, inside the footprint
    double solidMean = 0;  ///< engine's mean visibility where the reference is in shadow
    int holes = 0;         ///< footprint pixels the reference sees lit (under hole cells)
    int solids = 0;        ///< footprint pixels the reference sees in shadow
};

Agreement compare(Scene& scene, const FrameImages& images, const CameraView& view) {
    reference::ReferenceOptions options;
    options.width = kWidth;
    options.height = kHeight;
    options.samples = 1;
    options.wsPositions = &images.position;
    auto ref = reference::traceVisibility(scene, view, options);
    EXPECT_TRUE(static_cast<bool>(ref)) << (ref ? "" : ref.error().message);
    Agreement a;
    if (!ref) return a;
    const ImageF& rv = ref->visibility.at(0);
    const auto refAt = [&](int x, int y) { return rv.at(x, y, 0); };
    // The footprint: pixels within 3 px of a reference shadow pixel (so hole cells inside the
    // checker count, the open ground around it does not).
    int holes = 0;
    int solids = 0;
    for (int y = 3; y < kHeight - 3; ++y) {
        for (int x = 3; x < kWidth - 3; ++x) {
            if (!isGroundPixel(images, x, y)) continue;
            bool near = false;
            for (int dy = -3; dy <= 3 && !near; ++dy) {
                for (int dx = -3; dx <= 3 && !near; ++dx) near = refAt(x + dx, y + dy) < 0.5f;
            }
            if (!near) continue;
            // Inside the checker: a shadow pixel on both sides within 20 px (hole cells are 16
            // texels of the quad, ~25 px on screen).
            bool left = false;
            bool right = false;
            for (int d = 1; d <= 30; ++d) {
                left = left || (x - d >= 0 && refAt(x - d, y) < 0.5f);
                right = right || (x + d < kWidth && refAt(x + d, y) < 0.5f);
            }
            if (!left || !right) continue;
            const float v = images.visibility.at(0).at(x, y, 0);
            const float r = refAt(x, y);
            ++a.pixels;
            if ((v > 0.5f) != (r > 0.5f)) ++a.mismatches;
            if (r > 0.5f) {
                a.holeMean += v;
                ++holes;
            } else {
                a.solidMean += v;
                ++solids;
            }
        }
    }
    a.holeMean = holes > 0 ? a.holeMean / holes : 0.0;
    a.solidMean = solids > 0 ? a.solidMean / solids : 1.0;
    a.holes = holes;
    a.solids = solids;
    return a;
}

struct CutoutCase {
    LightType type;
    ShadowTechnique technique;
};

class CutoutShadow : public ::testing::TestWithParam<CutoutCase> {};

// A cut-out caster casts the shadow of its opaque cells only. Tolerances: mismatches (the two
// sides of 0.5 differ) at most 12 % of the checker's pixels: the edges of 32 cell borders, where a
// map places an edge to within a texel and a filtering technique widens it (measured 1-7 %);
// holes at least 0.8 lit on average and solid cells at most 0.2 (measured >= 0.9 / <= 0.1).
TEST_P(CutoutShadow, CheckerboardAlphaCastsCheckerboardShadow) {
    glContext();
    const CutoutCase c = GetParam();
    Scene scene = cutoutScene(c.type, c.technique);
    FrameRunner runner;
    const RenderedFrame frame = renderFrame(runner, scene, kWidth, kHeight);
    const Agreement a = compare(scene, frame.images, runner.lastCamera());
    ASSERT_GT(a.holes, 100) << "the footprint must hold hole cells";
    ASSERT_GT(a.solids, 500) << "the footprint must hold solid cells";
    const double mismatch = static_cast<double>(a.mismatches) / a.pixels;
    RecordProperty("mismatch", std::to_string(mismatch));
    EXPECT_LE(mismatch, 0.12) << techniqueName(c.technique) << " " << lightTypeName(c.type);
    EXPECT_GE(a.holeMean, 0.8) << "holes must let the light through";
    EXPECT_LE(a.solidMean, 0.2) << "solid cells must cast";
    std::printf("%s %s: mismatch %.3f, holes %.3f, solid %.3f\n", lightTypeName(c.type), techniqueName(c.technique),
                mismatch, a.holeMean, a.solidMean);
}

std::vector<CutoutCase> cutoutCases() {
    std::vector<CutoutCase> cases;
    for (LightType type : {LightType::Directional, LightType::Spot, LightType::Point}) {
        for (ShadowTechnique t :
             {ShadowTechnique::Hard, ShadowTechnique::Pcf, ShadowTechnique::Pcss, ShadowTechnique::Vsm,
              ShadowTechnique::Vssm, ShadowTechnique::Msm, ShadowTechnique::MsmSoft, ShadowTechnique::Sdf}) {
            cases.push_back({type, t});
        }
    }
    return cases;
}

INSTANTIATE_TEST_SUITE_P(EveryTechniqueAndType, CutoutShadow, ::testing::ValuesIn(cutoutCases()),
                         [](const ::testing::TestParamInfo<CutoutCase>& param) {
                             std::string name = std::string(lightTypeName(param.param.type)) + "_" +
                                                techniqueName(param.param.technique);
                             for (char& ch : name) {
                                 if (ch == '-') ch = '_';
                             }
                             return name;
                         });

// A material whose alpha is opaque (mode OPAQUE) casts its whole quad, whatever the texture says.
TEST(CutoutOpaque, OpaqueModeIgnoresAlpha) {
    glContext();
    Scene scene = cutoutScene(LightType::Directional, ShadowTechnique::Hard);
    scene.world.view<Material>().each([](Entity, Material& m) { m.alphaMode = AlphaMode::Opaque; });
    FrameRunner runner;
    const RenderedFrame frame = renderFrame(runner, scene, kWidth, kHeight);
    const Agreement a = compare(scene, frame.images, runner.lastCamera());
    ASSERT_GT(a.solids, 500);
    EXPECT_EQ(a.holes, 0) << "the reference sees no hole either";
    EXPECT_LE(static_cast<double>(a.mismatches) / a.pixels, 0.05);
    EXPECT_LE(a.solidMean, 0.1);
}

// ---- skinning ----

/// A bar along +x, [0, 2] x [-0.1, 0.1] x [-0.3, 0.3], in 8 slices: each slice's vertices follow
/// joint 0 (the root, at x = 0) and joint 1 (at x = 1) by a weight ramping over x in [0.5, 1.5].
std::shared_ptr<MeshData> skinnedBar() {
    auto box = makeBoxMesh(glm::vec3(0.125f, 0.1f, 0.3f));
    auto m = std::make_shared<MeshData>();
    m->name = "bar";
    for (int s = 0; s < 8; ++s) {
        const auto base = static_cast<std::uint32_t>(m->positions.size());
        const float cx = 0.125f + 0.25f * static_cast<float>(s);
        for (std::size_t i = 0; i < box->positions.size(); ++i) {
            glm::vec3 p = box->positions[i] + glm::vec3(cx, 0.0f, 0.0f);
            m->positions.push_back(p);
            m->normals.push_back(box->normals[i]);
            const float w1 = glm::clamp(p.x - 0.5f, 0.0f, 1.0f);
            m->joints.emplace_back(0, 1, 0, 0);
            m->weights.emplace_back(1.0f - w1, w1, 0.0f, 0.0f);
        }
        for (const std::uint32_t i : box->indices) m->indices.push_back(base + i);
    }
    computeBounds(*m);
    computeJointBounds(*m);
    return m;
}

struct SkinnedScene {
    Scene scene;
    Entity bar, root, elbow;
};

SkinnedScene skinnedScene(ShadowTechnique technique) {
    SkinnedScene s;
    addGround(s.scene, 4.0f);
    s.root = s.scene.world.create();
    s.scene.world.emplace<Transform>(s.root, placed({-1.0, 1.0, 0.0}));
    s.elbow = s.scene.world.create();
    Transform elbow = placed({1.0, 0.0, 0.0});
    elbow.parent = s.root;
    s.scene.world.emplace<Transform>(s.elbow, elbow);
    // The mesh instance's own transform is not applied to a skinned mesh (glTF): put it anywhere.
    s.bar = addMeshInstance(s.scene.world, "bar", skinnedBar(), placed({50.0, 50.0, 50.0}));
    Skin skin;
    skin.joints = {s.root, s.elbow};
    // Mesh space is the root's own: jointWorld * inverseBind places the mesh at the root in the
    // bind pose (the elbow 1 m along x from the root).
    skin.inverseBind = {glm::dmat4(1.0), glm::translate(glm::dmat4(1.0), glm::dvec3(-1.0, 0.0, 0.0))};
    s.scene.world.emplace<Skin>(s.bar, skin);
    Shadow shadow;
    shadow.technique = technique;
    shadow.mapSize = 1024;
    addLight(s.scene, "sun", pointSizedLight(LightType::Directional), shadow, {0, 10, 0},
             glm::normalize(glm::dvec3(0.1, -1.0, 0.05)));
    addCamera(s.scene, "camera", Camera{}, {0.0, 5.0, 3.0}, {0.0, 0.0, 0.0});
    return s;
}

// The shadow of a skinned bar follows its joints: bent 90 degrees up at the elbow, the far half
// stands over the elbow and its shadow shrinks to the near half's; the engine agrees with the
// reference's CPU skinning in both poses (mismatches at most 6 % of the shadow: its outline to
// within a texel and the rasteriser's edge rule; measured 2-3 %).
TEST(SkinnedShadow, FollowsTheJointsAndAgreesWithTheReference) {
    glContext();
    SkinnedScene s = skinnedScene(ShadowTechnique::Hard);
    FrameRunner runner;
    const RenderedFrame straight = renderFrame(runner, s.scene, kWidth, kHeight);
    const GroundAgreement a = groundAgreement(s.scene, runner.lastCamera(), straight.images);
    s.scene.world.get<Transform>(s.elbow).rotation = glm::angleAxis(glm::radians(90.0), glm::dvec3(0.0, 0.0, 1.0));
    const RenderedFrame bent = renderFrame(runner, s.scene, kWidth, kHeight);
    const GroundAgreement b = groundAgreement(s.scene, runner.lastCamera(), bent.images);
    std::printf("straight: %d shadowed (reference %d, %d mismatches); bent: %d (reference %d, %d mismatches)\n",
                a.shadowed, a.referenceShadowed, a.mismatches, b.shadowed, b.referenceShadowed, b.mismatches);
    ASSERT_GT(a.referenceShadowed, 500);
    EXPECT_LE(a.mismatches, 0.06 * a.referenceShadowed);
    EXPECT_LE(b.mismatches, 0.06 * a.referenceShadowed);
    // Bent, the far half's shadow is gone: about half the straight bar's (the near half and the
    // upright half's small footprint), and the reference says how much.
    EXPECT_LT(b.referenceShadowed, 0.75 * a.referenceShadowed);
    EXPECT_NEAR(b.shadowed, b.referenceShadowed, 0.06 * a.referenceShadowed);
    EXPECT_GT(bent.stats.shadowLayersDrawn, 0) << "a joint moved: the layers it falls in are redrawn";
}

// A frame where no joint moved reuses every layer; a joint moving redraws them; the posed bounds
// hold every skinned vertex.
TEST(SkinnedShadow, LayersRedrawnOnlyWhenAJointMoved) {
    glContext();
    SkinnedScene s = skinnedScene(ShadowTechnique::Pcf);
    FrameRunner runner;
    (void)renderFrame(runner, s.scene, kWidth, kHeight);
    const RenderedFrame still = renderFrame(runner, s.scene, kWidth, kHeight);
    EXPECT_EQ(still.stats.shadowLayersDrawn, 0) << "nothing moved";
    EXPECT_GT(still.stats.shadowLayersReused, 0);
    s.scene.world.get<Transform>(s.elbow).rotation = glm::angleAxis(0.3, glm::dvec3(0.0, 0.0, 1.0));
    const RenderedFrame moved = renderFrame(runner, s.scene, kWidth, kHeight);
    EXPECT_GT(moved.stats.shadowLayersDrawn, 0) << "the elbow moved";

    const Skin& skin = s.scene.world.get<Skin>(s.bar);
    ASSERT_TRUE(skin.posed);
    const DAabb& box = s.scene.world.get<WorldBounds>(s.bar).box;
    const MeshData& data = *s.scene.world.get<Mesh>(s.bar).data;
    for (std::size_t i = 0; i < data.positions.size(); ++i) {
        const glm::dvec3 p(skin.worldFromFrame *
                           glm::dvec4(glm::dvec3(skinnedPosition(data, skin, i, data.positions[i])), 1.0));
        EXPECT_TRUE(glm::all(glm::greaterThanEqual(p, box.min - 1e-5)) &&
                    glm::all(glm::lessThanEqual(p, box.max + 1e-5)))
            << "vertex " << i << " outside the posed bounds";
    }
}

// A skin with a joint whose transform is not finite is not drawn (and warned), nothing else harmed.
TEST(SkinnedShadow, NonFiniteJointSkipsTheMesh) {
    glContext();
    SkinnedScene s = skinnedScene(ShadowTechnique::Hard);
    s.scene.world.get<Transform>(s.elbow).translation.x = std::nan("");
    FrameRunner runner;
    const RenderedFrame frame = renderFrame(runner, s.scene, kWidth, kHeight);
    EXPECT_FALSE(s.scene.world.get<Skin>(s.bar).posed);
    int shadowed = 0;
    for (int y = 0; y < kHeight; ++y) {
        for (int x = 0; x < kWidth; ++x) {
            if (isGroundPixel(frame.images, x, y) && frame.images.visibility.at(0).at(x, y, 0) < 0.5f) ++shadowed;
        }
    }
    EXPECT_EQ(shadowed, 0);
}

}  // namespace
}  // namespace shadow::test::cutout_skin_test
