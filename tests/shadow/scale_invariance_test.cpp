// The same scene at 1/100, 1 and 100 times its size casts the same shadows with every technique
// at its default settings: every length the module derives by default (biases, filter radii,
// the distance-field march's offsets, near planes, cascade fits) follows the scene, none is a
// fixed number of metres. The scaled copy multiplies every root transform's translation, every
// root mesh's scale, every emitter radius and range, the lengths of procedural motions, and the
// camera's clip planes by the factor; angles (a sun's angular radius, cone angles) stay.
//
// Three scenes: the plates under a disk spot, the default scene (boxes, some moving, under a
// cascaded sun, a spot and a point light) and, in the slow tier, the bunny under the same three
// light types (a real mesh, whose distance field takes a second to bake for each scale).
#include <gtest/gtest.h>
#include <shadow/scene.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "render/render_test_support.h"
#include "shadow/soft_test_support.h"
#include "test_support.h"

namespace shadow::test::scale_invariance_test {
namespace {

/// Multiplies every length of `scene` by `k` (see the file comment).
void scaleScene(Scene& scene, double k) {
    World& world = scene.world;
    world.view<Transform>().each([&](Entity e, Transform& t) {
        if (!t.parent.isNull()) return;  // children follow their scaled parents
        t.translation *= k;
        if (world.has<Mesh>(e)) t.scale *= k;
    });
    world.view<Light>().each([&](Entity, Light& l) {
        l.radius = static_cast<float>(l.radius * k);
        l.range = static_cast<float>(l.range * k);
    });
    world.view<ProceduralMotion>().each([&](Entity, ProceduralMotion& m) {
        m.center *= k;
        m.radius *= k;
        m.amplitude *= k;
    });
    world.view<Camera>().each([&](Entity, Camera& c) {
        c.znear = static_cast<float>(c.znear * k);
        c.zfar = static_cast<float>(c.zfar * k);
    });
}

/// Every shadowed light of `scene` at `technique` with the defaults, on maps of `mapSize`.
void useDefaults(Scene& scene, ShadowTechnique technique, int mapSize) {
    scene.world.view<Shadow>().each([&](Entity, Shadow& s) {
        const int cascades = s.cascades;
        s = shadowWith(technique, mapSize);
        s.cascades = cascades;
    });
}

struct Difference {
    double worstFraction = 0.0;  ///< the largest fraction of covered pixels differing by > 1/255
    std::size_t worstLight = 0;
};

/// Per light, the fraction of pixels covered in both images whose visibility differs by more
/// than 1/255; the worst light's.
Difference compare(const FrameImages& a, const FrameImages& b) {
    Difference d;
    for (std::size_t i = 0; i < a.visibility.size(); ++i) {
        long covered = 0;
        long differ = 0;
        for (int y = 0; y < a.position.height; ++y) {
            for (int x = 0; x < a.position.width; ++x) {
                if (a.position.at(x, y, 3) < 0.5f || b.position.at(x, y, 3) < 0.5f) continue;
                ++covered;
                if (std::abs(a.visibility[i].at(x, y, 0) - b.visibility[i].at(x, y, 0)) > 1.0f / 255.0f) ++differ;
            }
        }
        const double fraction = covered > 0 ? static_cast<double>(differ) / static_cast<double>(covered) : 1.0;
        if (fraction >= d.worstFraction) d = {fraction, i};
    }
    return d;
}

/// Renders scene `name` at scale 1, 0.01 and 100 for every technique and checks that at most 1 %
/// of the pixels differ by more than 1/255 in any light's visibility.
void expectScaleFree(const std::string& name, int mapSize) {
    constexpr int kWidth = 128;
    constexpr int kHeight = 96;
    constexpr double kMostDiffering = 0.01;
    const std::vector<double> scales{1.0, 0.01, 100.0};
    std::vector<Scene> scenes;  // made once: the technique is all that changes between frames
    for (double k : scales) {
        Result<Scene> scene = makeBuiltinScene(name);
        ASSERT_TRUE(scene) << scene.error().message;
        scaleScene(*scene, k);
        scenes.push_back(std::move(scene).value());
    }
    for (ShadowTechnique technique :
         offered({ShadowTechnique::Hard, ShadowTechnique::Pcf, ShadowTechnique::Pcss, ShadowTechnique::Vsm,
                  ShadowTechnique::Vssm, ShadowTechnique::Msm, ShadowTechnique::MsmSoft, ShadowTechnique::Sdf})) {
        std::vector<FrameImages> images;
        for (Scene& scene : scenes) {
            useDefaults(scene, technique, mapSize);
            images.push_back(renderOnce(scene, kWidth, kHeight));
        }
        for (std::size_t s = 1; s < images.size(); ++s) {
            const Difference d = compare(images[0], images[s]);
            EXPECT_LE(d.worstFraction, kMostDiffering)
                << name << ", " << techniqueName(technique) << ", scale " << scales[s] << ": light " << d.worstLight
                << " differs from scale 1 by more than 1/255 at " << 100.0 * d.worstFraction << " % of the pixels";
        }
    }
}

TEST(ScaleInvariance, PlatesCastTheSameShadowsAtAHundredthAndAHundredTimesTheirSize) { expectScaleFree("plates", 512); }

TEST(ScaleInvariance, DefaultSceneUnderThreeLightTypesCastsTheSameShadowsAtAnyScale) {
    expectScaleFree("default", 512);
}

TEST(ScaleInvariance, SlowBunnyUnderThreeLightTypesCastsTheSameShadowsAtAnyScale) {
    if (!std::filesystem::exists(kBunnyObjPath)) GTEST_SKIP() << "no " << kBunnyObjPath;
    expectScaleFree("bunny", 512);
}

}  // namespace
}  // namespace shadow::test::scale_invariance_test
