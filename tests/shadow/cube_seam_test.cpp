// Where a point light's cube faces meet: a wall's penumbra on the ground crosses the boundary
// between the -Y face (under the light) and the +X face, and its profile just either side of the
// boundary is compared with the profile either side of a line inside one face. PCF and PCSS
// route each tap to its own face. A moment technique reads its region from the receiver's face
// alone, a square (VSSM) or four fetches (MSM-soft) of that face's texel grid, not a disk: near
// the boundary the region is cut at the face's edge, and the wall's edge runs along one face's
// grid and across the other's diagonally, so the two faces blur it differently. Faces widened by
// twice maxFilterTexels (no region cut) took the jump to 0.038 (VSSM) and 0.066 (MSM-soft, its
// search region as quadrants too), but
// cost the point lights of builtin:bunny and builtin:default a quarter of their texels: RMSE
// against the ray-traced truth 0.078 -> 0.083 and 0.151 -> 0.171 (VSSM), 0.079 -> 0.117 and
// 0.152 -> 0.192 (MSM-soft); not kept. This test holds the seams to what they measure.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "shadow/soft_test_support.h"

namespace shadow::cube_seam_test {
namespace {

constexpr double kLightHeight = 3.0;
/// The -Y face and the +X face meet on the ground along x = kLightHeight (45 degrees).
constexpr double kSeamX = kLightHeight;
/// A line inside the -Y face, for comparison.
constexpr double kControlX = 2.0;
/// The wall's top edge at height 1.2 m, z = 1.05 m: its shadow edge on the ground is the line
/// z = 1.05 * 3 / 1.8 = 1.75 m whatever x, with a penumbra 2 R (3 - 1.8) / 1.8 = 0.2 m wide.
constexpr double kEdgeZ = 1.75;

/// Largest difference between the mean visibility profiles across the shadow edge (bins of z
/// over [kEdgeZ - 0.3, kEdgeZ + 0.3]) of the ground pixels just left and just right of x = `at`.
double profileJump(const FrameImages& im, double at) {
    constexpr int kBins = 12;
    test::Profile left(kEdgeZ - 0.3, kEdgeZ + 0.3, kBins);
    test::Profile right(kEdgeZ - 0.3, kEdgeZ + 0.3, kBins);
    for (int y = 0; y < im.position.height; ++y) {
        for (int x = 0; x < im.position.width; ++x) {
            if (!test::isGroundPixel(im, x, y)) continue;
            const glm::dvec3 p = test::positionAt(im, x, y);
            const double d = p.x - at;
            if (d > -0.12 && d < -0.02) left.add(p.z, im.visibility[0].at(x, y, 0));
            if (d > 0.02 && d < 0.12) right.add(p.z, im.visibility[0].at(x, y, 0));
        }
    }
    double jump = 0.0;
    int bins = 0;
    for (int b = 0; b < kBins; ++b) {
        const auto l = left.mean(b);
        const auto r = right.mean(b);
        if (!l || !r) continue;
        jump = std::max(jump, std::abs(*l - *r));
        ++bins;
    }
    EXPECT_GE(bins, kBins - 1) << "too few ground pixels beside x = " << at;
    return jump;
}

/// Largest jump (visibility) allowed across the face boundary beyond the jump across the
/// control line inside one face, per technique: measured on llvmpipe (the "[ measured ]" lines:
/// PCSS 0.019, VSM 0.105, VSSM 0.064, MSM-soft 0.094; control lines 0.004-0.006), with room for
/// a quarter more.
double seamAllowance(ShadowTechnique t) {
    switch (t) {
        case ShadowTechnique::Pcss: return 0.025;
        case ShadowTechnique::Vsm: return 0.13;
        case ShadowTechnique::Vssm: return 0.08;
        default: return 0.12;  // MsmSoft
    }
}

TEST(CubeSeam, PenumbraAcrossAFaceBoundaryJumpsNoMoreThanMeasured) {
    test::glContext();
    for (ShadowTechnique technique :
         {ShadowTechnique::Pcss, ShadowTechnique::Vsm, ShadowTechnique::Vssm, ShadowTechnique::MsmSoft}) {
        Scene scene;
        test::addGround(scene, 8.0f);
        test::addBox(scene, "wall", {3.5, 0.6, 1.0}, {3.0, 0.6, 0.05});
        Light bulb = test::pointSizedLight(LightType::Point);
        bulb.radius = 0.1f;
        Shadow shadow = test::shadowWith(technique, 512);
        shadow.maxFilterTexels = 16.0f;
        shadow.pcfRadius = 0.04f;  // VSM's fixed filter: about 2-4 texels here
        addLight(scene, "bulb", bulb, shadow, {0.0, kLightHeight, 0.0}, {0, -1, 0});
        Camera lens;
        lens.yfov = 0.5f;
        const Entity camera = addCamera(scene, "camera", lens, {2.5, 3.0, 3.2}, {2.5, 0.0, kEdgeZ});
        FrameRunner runner;
        const test::RenderedFrame frame = test::renderFrame(runner, scene, 256, 192, 0.0, camera);
        test::expectSaneAovs(frame.images);
        const double seam = profileJump(frame.images, kSeamX);
        const double control = profileJump(frame.images, kControlX);
        std::printf("[ measured ] %s: profile jump across the face boundary %.4f, across a line inside a face %.4f\n",
                    techniqueName(technique), seam, control);
        EXPECT_LT(seam, control + seamAllowance(technique)) << techniqueName(technique);
    }
}

}  // namespace
}  // namespace shadow::cube_seam_test
