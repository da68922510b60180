// What the viewer-script fuzzer does with one input: the bytes as a script for the viewer
// (samples/viewer_script.h), parsed and checked against builtin:default (a sun, a spot and a
// point light, one camera). A script that is refused must say so in one capped message naming
// the file and line; one that is accepted must hold only commands inside the checked ranges, and
// its `set` commands are written into the lights as the viewer writes them (unclamped), then the
// CPU half of a few frames runs with the planner's promises checked (gltf_fuzz_target.h): every
// setting the script language accepts, in any combination, is one the planner copes with. The
// lights are restored after each input. Shared by tests/fuzz/script_fuzzer.cpp and the GoogleTest
// that replays the seed scripts (script_fuzz_test.cpp).
#pragma once

#include <shadow/scene.h>

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "fuzz/gltf_fuzz_target.h"
#include "viewer_script.h"
#include "viewer_settings.h"

namespace shadow::fuzz {

/// The scene scripts are checked against, and its lights' components as loaded.
struct ScriptScene {
    Scene scene;
    std::vector<std::pair<Light, std::optional<Shadow>>> loaded;

    ScriptScene() {
        Result<Scene> s = loadScene("builtin:default");
        check(s.ok(), "builtin:default loads");
        scene = std::move(*s);
        if (scene.cameras.empty()) (void)addDefaultCamera(scene);
        for (const Entity e : scene.lights) {
            const Shadow* shadow = scene.world.tryGet<Shadow>(e);
            loaded.emplace_back(scene.world.get<Light>(e), shadow ? std::optional<Shadow>(*shadow) : std::nullopt);
        }
    }
    /// Puts every light back as loaded.
    void restore() {
        for (std::size_t i = 0; i < scene.lights.size(); ++i) {
            const Entity e = scene.lights[i];
            scene.world.get<Light>(e) = loaded[i].first;
            if (loaded[i].second) {
                scene.world.emplaceOrReplace<Shadow>(e, *loaded[i].second);
            } else {
                (void)scene.world.remove<Shadow>(e);
            }
        }
    }
};

inline ScriptScene& scriptScene() {
    static ScriptScene s;
    return s;
}

/// One fuzz input. Returns the parse's result (for the tests); never throws, aborts only on a
/// broken invariant (or a sanitizer report).
inline Result<std::vector<viewer::ScriptCommand>> runScriptInput(const std::uint8_t* data, std::size_t size) {
    using Verb = viewer::ScriptCommand::Verb;
    ScriptScene& s = scriptScene();
    const std::string text(reinterpret_cast<const char*>(data), size);
    const int lights = static_cast<int>(s.scene.lights.size());
    const int cameras = static_cast<int>(s.scene.cameras.size());
    Result<std::vector<viewer::ScriptCommand>> commands =
        viewer::parseScript(text, "fuzz.script", viewer::ScriptContext{lights, cameras});
    if (!commands) {
        const std::string& message = commands.error().message;
        check(message.size() <= viewer::kMaxScriptMessage, "a script error is capped");
        check(message.rfind("fuzz.script:", 0) == 0, "a script error names the file and line");
        return commands;
    }
    const auto lightIndex = [&](const viewer::ScriptCommand& c) {
        return c.index.has_value() && *c.index >= 0 && *c.index < lights;
    };
    bool wrote = false;
    for (const viewer::ScriptCommand& c : *commands) {
        check(c.line >= 1, "a command has its line");
        check(std::isfinite(c.number), "a command's number is finite");
        switch (c.verb) {
            case Verb::Time: check(c.number >= 0.0, "time >= 0"); break;
            case Verb::Dt: check(c.number > 0.0, "dt > 0"); break;
            case Verb::Frames: check(c.number >= 1.0 && c.number <= 100000.0, "frames in [1, 100000]"); break;
            case Verb::Exposure: check(!c.index || c.number > 0.0, "exposure > 0 or auto"); break;
            case Verb::Camera:
                check(c.index.has_value() && *c.index >= 0 && *c.index < cameras, "camera index in range");
                break;
            case Verb::ShadowMap:
                check(!c.index || (lightIndex(c) && c.number >= 0.0 && c.number <= 5.0), "shadowmap light and layer");
                break;
            case Verb::Debug: check(!c.index || lightIndex(c), "debug light in range"); break;
            case Verb::Screenshot:
            case Verb::ScreenshotUi: check(c.path.size() >= 5, "screenshot path"); break;
            case Verb::Set: {
                check(!c.index || lightIndex(c), "set light in range");
                const viewer::LightSetting* setting = viewer::findLightSetting(c.key);
                check(setting != nullptr, "set names a known key");
                for (int i = 0; i < lights; ++i) {
                    if (!c.index || *c.index == i) {
                        viewer::writeSetting(s.scene.world, s.scene.lights[static_cast<std::size_t>(i)], *setting,
                                             c.number);
                    }
                }
                wrote = true;
                break;
            }
            case Verb::Quit: break;
        }
    }
    if (wrote) {
        runCpuFrames(s.scene);
        s.restore();
    }
    return commands;
}

}  // namespace shadow::fuzz
