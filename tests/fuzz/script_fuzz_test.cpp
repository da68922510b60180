// The viewer-script fuzz target (script_fuzz_target.h) in every ordinary build: its seed scripts
// (tests/fuzz/scripts/) are accepted, cover every command and every light setting, and their
// settings are planned; a refused script names its line and writes nothing; the lights are put
// back after each input, so that inputs do not depend on the ones before.
#include <gtest/gtest.h>

#include <filesystem>
#include <set>
#include <string>
#include <vector>

#include "fuzz/fuzz_test_support.h"
#include "fuzz/script_fuzz_target.h"

namespace shadow::script_fuzz_test {
namespace {

namespace fs = std::filesystem;
using Verb = viewer::ScriptCommand::Verb;

/// The seed scripts' texts.
std::vector<std::string> seedScripts() {
    std::vector<std::string> texts;
    for (const fs::path& p : fuzz_test::inputsIn(SHADOW_FUZZ_DIR "/scripts")) {
        if (p.extension() == ".script") texts.push_back(fuzz_test::bytesOf(p));
    }
    return texts;
}

Result<std::vector<viewer::ScriptCommand>> run(const std::string& text) {
    return fuzz::runScriptInput(reinterpret_cast<const std::uint8_t*>(text.data()), text.size());
}

int mapSizeOf(int light) {
    const fuzz::ScriptScene& s = fuzz::scriptScene();
    const Shadow* shadow = s.scene.world.tryGet<Shadow>(s.scene.lights.at(static_cast<std::size_t>(light)));
    return shadow != nullptr ? shadow->mapSize : Shadow{}.mapSize;
}

TEST(ScriptFuzz, EverySeedIsAcceptedAndTheSeedsHoldEveryCommandAndSetting) {
    const std::vector<std::string> seeds = seedScripts();
    ASSERT_GE(seeds.size(), 3U) << SHADOW_FUZZ_DIR "/scripts";
    std::set<Verb> verbs;
    std::set<std::string> keys;
    for (const std::string& text : seeds) {
        const auto commands = run(text);
        ASSERT_TRUE(commands.ok()) << commands.error().message;
        for (const viewer::ScriptCommand& c : *commands) {
            verbs.insert(c.verb);
            if (c.verb == Verb::Set) keys.insert(c.key);
        }
    }
    // The fuzzer starts from these: a command or a key missing here is one it must find alone.
    EXPECT_EQ(verbs.size(), 11U) << "a seed script for each of the 11 commands";
    for (const viewer::LightSetting& setting : viewer::lightSettings()) {
        EXPECT_EQ(keys.count(setting.key), 1U) << "no seed script sets " << setting.key;
    }
}

TEST(ScriptFuzz, ARefusedScriptNamesItsLineAndWritesNothing) {
    const int before = mapSizeOf(1);
    const auto refused = run("time 1\nset 1 mapSize 64\nframes 0\n");
    ASSERT_FALSE(refused.ok());
    EXPECT_EQ(refused.error().message.rfind("fuzz.script:3: ", 0), 0U) << refused.error().message;
    EXPECT_EQ(mapSizeOf(1), before);
}

TEST(ScriptFuzz, TheLightsArePutBackAfterAnAcceptedScript) {
    const int before = mapSizeOf(1);
    ASSERT_NE(before, 64);
    const auto accepted = run("set 1 mapSize 64\n");
    ASSERT_TRUE(accepted.ok()) << accepted.error().message;
    EXPECT_EQ(mapSizeOf(1), before);
    // A setting that only the written one turns on (a technique) comes back too.
    const fuzz::ScriptScene& s = fuzz::scriptScene();
    const Shadow* shadow = s.scene.world.tryGet<Shadow>(s.scene.lights.at(0));
    const ShadowTechnique technique = shadow != nullptr ? shadow->technique : Shadow{}.technique;
    ASSERT_TRUE(run("set 0 technique " + std::string(technique == ShadowTechnique::Pcf ? "hard" : "pcf")).ok());
    shadow = s.scene.world.tryGet<Shadow>(s.scene.lights.at(0));
    EXPECT_EQ(shadow != nullptr ? shadow->technique : Shadow{}.technique, technique);
}

}  // namespace
}  // namespace shadow::script_fuzz_test
