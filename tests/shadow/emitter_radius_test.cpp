// PCF and VSM at their default radius (the penumbra of the light's emitter from a typical caster,
// engine/src/shadow/emitter_radius.h) against the ray-traced truth on the two plates scenes,
// whose casters float over the receiver: the fixed-width filters must come well below hard
// shadows there (a radius of one texel, the default before, gave hard's error to within 2 %).
#include <gtest/gtest.h>
#include <shadow/scene.h>

#include <cstdio>
#include <string>
#include <vector>

#include "shadow/truth_test_support.h"

namespace shadow::test::emitter_radius_test {
namespace {

/// Light 0's RMSE under hard, PCF and VSM at their defaults on builtin:`name`, 160x120, against
/// 64 rays a pixel; PCF's and VSM's at most `most` times hard's.
void expectFixedFiltersBelowHard(const std::string& name, double most) {
    Result<Scene> scene = makeBuiltinScene(name);
    ASSERT_TRUE(scene) << scene.error().message;
    const std::vector<ShadowTechnique> techniques{ShadowTechnique::Hard, ShadowTechnique::Pcf, ShadowTechnique::Vsm};
    const std::vector<AgainstTruth> errors = renderAgainstTruth(*scene, 160, 120, 64, techniques);
    const double hard = errors.at(0).errors.rmse;
    std::printf("[ measured ] %s, hard: RMSE %.4f\n", name.c_str(), hard);
    for (std::size_t i = 1; i < techniques.size(); ++i) {
        const double rmse = errors.at(i).errors.rmse;
        std::printf("[ measured ] %s, %s at its default radius: RMSE %.4f (%.2f of hard's)\n", name.c_str(),
                    techniqueName(techniques[i]), rmse, rmse / hard);
        EXPECT_LE(rmse, most * hard) << name << ", " << techniqueName(techniques[i]);
    }
}

TEST(EmitterRadius, PcfAndVsmAtTheirDefaultsFollowThePlatesPenumbrae) { expectFixedFiltersBelowHard("plates", 0.6); }

TEST(EmitterRadius, PcfAndVsmAtTheirDefaultsFollowThePlateBoxesPenumbrae) {
    expectFixedFiltersBelowHard("plates-boxes", 0.8);
}

}  // namespace
}  // namespace shadow::test::emitter_radius_test
