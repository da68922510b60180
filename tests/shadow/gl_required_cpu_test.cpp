// The GL-side types used before `loadGl` (this binary never loads GL): one clear GlError naming
// the type and the missing step, not a call through a null entry point.
#include <gtest/gtest.h>
#include <shadow/context.h>
#include <shadow/frame_runner.h>
#include <shadow/mesh_cache.h>
#include <shadow/renderer.h>
#include <shadow/shadow_system.h>

#include <functional>
#include <string>

namespace shadow {
namespace {

void expectLoadGlError(const std::function<void()>& make, const std::string& who) {
    try {
        make();
        ADD_FAILURE() << who << " was built without GL";
    } catch (const GlError& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find(who), std::string::npos) << message;
        EXPECT_NE(message.find("loadGl"), std::string::npos) << message;
    }
}

TEST(GlRequired, EngineTypesBuiltBeforeLoadGlThrowAClearError) {
    expectLoadGlError([] { ShadowSystem s; }, "ShadowSystem");
    expectLoadGlError([] { MeshCache m; }, "MeshCache");
    expectLoadGlError([] { Renderer r; }, "Renderer");
    expectLoadGlError([] { FrameRunner f; }, "ShadowSystem");  // its first GL member
}

}  // namespace
}  // namespace shadow
