// Replays every input of tests/fuzz/regressions/ (inputs that once crashed gltf_fuzzer) and
// tests/fuzz/corpus/ (its seeds) through the fuzzer's own body, in every ordinary build: each
// must load or fail with an error, never crash or break an invariant.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "fuzz/fuzz_test_support.h"
#include "fuzz/gltf_fuzz_target.h"

namespace shadow {
namespace {

namespace fs = std::filesystem;
using fuzz_test::bytesOf;
using fuzz_test::inputsIn;

TEST(GltfFuzzRegressions, EveryRegressionInputLoadsOrFailsCleanly) {
    const std::vector<fs::path> inputs = inputsIn(SHADOW_FUZZ_DIR "/regressions");
    // A missing or emptied folder would make this test pass while testing nothing.
    ASSERT_FALSE(inputs.empty()) << SHADOW_FUZZ_DIR "/regressions holds no inputs";
    for (const fs::path& p : inputs) {
        SCOPED_TRACE(p.filename().string());
        const std::string bytes = bytesOf(p);
        fuzz::runOneInput(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
        // Through the file path as well: the same answer as from memory, or an error.
        (void)loadGltf(p.string());
    }
    std::printf("[ measured ] %zu regression inputs replayed\n", inputs.size());
}

TEST(GltfFuzzRegressions, EverySeedOfTheCorpusLoads) {
    const std::vector<fs::path> seeds = inputsIn(SHADOW_FUZZ_DIR "/corpus");
    ASSERT_GE(seeds.size(), 3u);
    for (const fs::path& p : seeds) {
        SCOPED_TRACE(p.filename().string());
        const std::string bytes = bytesOf(p);
        fuzz::runOneInput(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
        // Seeds that are glTF documents are valid ones (the others are bare extras objects).
        if (p.extension() == ".gltf" || p.extension() == ".glb") {
            const Result<Scene> scene = gltf::loadGltfFromMemory(bytes, p.filename().string());
            EXPECT_TRUE(scene.ok()) << scene.error().message;
        }
    }
}

}  // namespace
}  // namespace shadow
