// The GL-side types used before `loadGl` (this binary never loads GL): one clear GlError naming
// the type and the missing step, not a call through a null entry point.
#include <gtest/gtest.h>
#include <shadow/context.h>
#include <shadow/frame_runner.h>
#include <shadow/mesh_cache.h>
#include <shadow/renderer.h>
#include <shadow/shadow_system.h>

#include <functional>
#include <utility>
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

TEST(GlRequired, WithoutExceptionsTheSameErrorComesBackAsAValue) {
    // The factories a game built without exceptions calls: no throw, the same message.
    // GlUnavailable (no GL to call, as loadGl's own failures say), the call named once.
    for (const auto& [result, who] : {std::pair{ShadowSystem::create().error(), "ShadowSystem"},
                                      std::pair{MeshCache::create().error(), "MeshCache"}}) {
        const std::string& error = result.message;
        EXPECT_EQ(result.code, ErrorCode::GlUnavailable) << error;
        EXPECT_EQ(error.find(who), 0u) << error;
        EXPECT_EQ(error.find(who, 1), std::string::npos) << "the call named twice: " << error;
        EXPECT_NE(error.find("loadGl"), std::string::npos) << error;
    }
    ShadowBindingPoints clash;
    clash.layerBlock = clash.lightBlock;
    const Result<std::string> source = tryShadowShaderSource(clash);
    ASSERT_FALSE(source.ok());
    EXPECT_NE(source.error().message.find("lightBlock"), std::string::npos) << source.error().message;
    EXPECT_TRUE(tryShadowShaderSource().ok());  // the embedded GLSL needs no GL to expand
}

}  // namespace
}  // namespace shadow
