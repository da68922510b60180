// shadow_viewer: the animated scenes in a window, with Dear ImGui panels to tune every light's
// shadow live, debug views, a shadow-map view and per-pass timing graphs; or, scripted, a run
// that needs no input (CI under Xvfb) and writes screenshots.
//
//   shadow_viewer [SCENE] [--size WxH] [--camera N] [--time T] [--technique NAME]
//                 [--debug VIEW] [--debug-light I] [--animation NAME|INDEX|all]
//                 [--no-default-lights] [--no-ground]
//                 [--script FILE | --frames N [--dt S]] [--screenshot DIR]
//
// SCENE is a sample scene's name, a .gltf/.glb path or builtin:NAME (default builtin:default); a .gltf/.glb dropped on
// the window replaces it (a scene that does not load is reported and the old one kept). A file
// without lights is lit by the default rig (shadow/default_rig.h), said in the Scene panel.
// Interactive controls: README.md, "The viewer". With --script FILE the viewer runs the script
// (viewer_script.h, docs/viewer.md) and exits; with --frames N it renders N frames from --time T
// in steps of --dt S and, with --screenshot DIR, writes DIR/color.png (the scene, tone-mapped as
// shadow_render's color.png) and DIR/color_ui.png (the window with the UI), then exits. Bad input:
// one message, exit code 2, nothing written.
#include "cli_common.h"
#include "command_line.h"
#include "render_output.h"
#include "viewer_app.h"
#include "viewer_script.h"
#include "viewer_settings.h"
#include "viewer_ui.h"

#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

namespace {

using namespace shadow;
using namespace shadow::viewer;

using samples::kExitBadInput;
using samples::kExitFailure;

struct Options {
    std::string scene = "builtin:default";
    std::optional<std::string> size;
    std::optional<int> camera;
    double time = 0.0;
    std::optional<std::string> technique;
    std::string debug = "none";
    int debugLight = 0;
    std::string script;
    std::optional<int> frames;
    double dt = 1.0 / 30.0;
    std::string screenshotDir;
    std::string screenVisibility = "auto";
    std::string animation;          ///< which clip plays: empty (the first), all, an index or a name
    samples::DefaultRigChoice rig;  ///< for a file without lights
};

int fail(int code, const std::string& message) { return samples::failAs("shadow_viewer", code, message); }

/// The loop's own state: the clock, the mouse drag and Dear ImGui's frame.
struct App {
    ViewerState state;
    std::chrono::steady_clock::time_point last = std::chrono::steady_clock::now();
    double lastFrameMs = 0.0;
    double cursorX = 0.0, cursorY = 0.0;
    bool dragging = false;  ///< a button went down over the scene, not over a panel
};

void cycleTechniques(ViewerState& state) {
    // Every shadowed light to the technique after the first one's, skipping none.
    std::optional<ShadowTechnique> next;
    state.scene.world.view<Shadow>().each([&](Entity, Shadow& s) {
        if (!next) {
            int t = static_cast<int>(s.technique);
            do {
                t = (t + 1) % kShadowTechniqueCount;
            } while (!techniqueAvailable(static_cast<ShadowTechnique>(t)) || t == 0);
            next = static_cast<ShadowTechnique>(t);
        }
        s.technique = *next;
    });
    if (next) state.status = std::string("every light: ") + techniqueName(*next);
}

void takeScreenshot(App& app) {
    // In the current folder, numbered from 0 per run.
    const std::string path = "shadow_viewer_" + std::to_string(app.state.screenshots++) + ".png";
    const Status s = writeFrameScreenshot(app.state, path);
    app.state.status = s ? "wrote " + path : "screenshot failed: " + s.error().message;
}

/// Keys and mouse of one interactive frame (none while a panel has the keyboard or mouse).
void handleInput(App& app, double dt) {
    ViewerState& state = app.state;
    Window& window = *state.window;
    const ImGuiIO& io = ImGui::GetIO();
    if (!io.WantCaptureKeyboard) {
        if (window.keyPressed(Window::Key::Escape)) window.requestClose();
        if (window.keyPressed(Window::Key::Pause)) state.paused = !state.paused;
        if (window.keyPressed(Window::Key::Screenshot)) takeScreenshot(app);
        if (window.keyPressed(Window::Key::ToggleUi)) state.showUi = !state.showUi;
        if (window.keyPressed(Window::Key::NextTechnique)) cycleTechniques(state);
        if (window.keyPressed(Window::Key::CameraMode)) {
            const bool toFly = state.rig.mode() != CameraRig::Mode::Fly;
            state.rig.setMode(state.scene.world, toFly ? CameraRig::Mode::Fly : CameraRig::Mode::Orbit);
        }
    }
    CameraInput in;
    in.dt = dt;
    auto axis = [&](Window::Key plus, Window::Key minus) {
        return (window.keyDown(plus) ? 1.0 : 0.0) - (window.keyDown(minus) ? 1.0 : 0.0);
    };
    if (!io.WantCaptureKeyboard) {
        in.fly = glm::dvec3(axis(Window::Key::Right, Window::Key::Left), axis(Window::Key::Up, Window::Key::Down),
                            axis(Window::Key::Forward, Window::Key::Back));
        in.fast = window.keyDown(Window::Key::Fast);
        if (in.fly != glm::dvec3(0.0) && state.rig.mode() != CameraRig::Mode::Fly) {
            state.rig.setMode(state.scene.world, CameraRig::Mode::Fly);
        }
    }
    double x = 0.0, y = 0.0;
    window.cursorPosition(x, y);
    const bool left = window.buttonDown(Window::Button::Left);
    const bool right = window.buttonDown(Window::Button::Right);
    const bool middle = window.buttonDown(Window::Button::Middle);
    if (!left && !right && !middle) {
        app.dragging = false;
    } else if (!app.dragging && !io.WantCaptureMouse) {
        app.dragging = true;
    }
    if (app.dragging) {
        in.dx = x - app.cursorX;
        in.dy = y - app.cursorY;
        in.turn = left;
        in.zoom = right;
        in.pan = middle;
    }
    app.cursorX = x;
    app.cursorY = y;
    const double scroll = window.takeScroll();
    if (!io.WantCaptureMouse) in.scroll = scroll;
    state.rig.update(state.scene.world, in);
}

/// Loads the files dropped on the window (each playing its first clip); the last that loads
/// wins, errors are shown.
void handleDrops(ViewerState& state) {
    for (const std::string& path : state.window->takeDroppedPaths()) {
        state.animation.clear();
        if (Status s = loadInto(state, path, std::nullopt); !s) {
            state.loadError = s.error().message;
        } else {
            state.loadError.clear();
            state.status = "loaded " + path;
            state.window->setTitle("shadow_viewer: " + path);
        }
    }
}

/// One frame: input, the scene, the UI, then `beforeSwap` (a screenshot of the window), the swap.
void frameStep(App& app, bool interactive, const std::function<void()>& beforeSwap = {}) {
    ViewerState& state = app.state;
    state.window->pollEvents();
    const auto now = std::chrono::steady_clock::now();
    const double dt = std::chrono::duration<double>(now - app.last).count();
    app.last = now;
    handleDrops(state);
    if (interactive) {
        handleInput(app, dt);
        if (!state.paused) state.time += dt * state.speed;
    }
    renderFrame(state, app.lastFrameMs);
    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
    UiRequests requests;
    drawUi(state, requests);
    ImGui::Render();
    clearWindow();
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
    if (beforeSwap) beforeSwap();
    state.window->swapBuffers();
    if (requests.screenshot) takeScreenshot(app);
    if (requests.reload) {
        const std::string spec = state.sceneSpec;  // loadInto replaces it
        if (Status s = loadInto(state, spec, std::nullopt); !s) state.loadError = s.error().message;
    }
    if (requests.sceneCamera && *requests.sceneCamera < static_cast<int>(state.scene.cameras.size())) {
        state.rig.reset(state.scene, state.scene.cameras[static_cast<std::size_t>(*requests.sceneCamera)]);
    }
    app.lastFrameMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - now).count();
}

/// Runs checked script commands; 0, or kExitFailure when a screenshot cannot be written.
int runScript(App& app, const std::vector<ScriptCommand>& commands) {
    using Verb = ScriptCommand::Verb;
    ViewerState& state = app.state;
    double dt = 1.0 / 30.0;
    for (const ScriptCommand& cmd : commands) {
        switch (cmd.verb) {
            case Verb::Time: state.time = cmd.number; break;
            case Verb::Dt: dt = cmd.number; break;
            case Verb::Frames:
                for (int k = 0; k < static_cast<int>(cmd.number); ++k) {
                    if (k > 0) state.time += dt;
                    frameStep(app, false);
                }
                break;
            case Verb::Set: {
                const LightSetting& setting = *findLightSetting(cmd.key);
                for (std::size_t i = 0; i < state.scene.lights.size(); ++i) {
                    const Entity e = state.scene.lights[i];
                    // `all` leaves lights without a shadow so, as shadow_render's --technique.
                    const bool all = !cmd.index;
                    if (!all && static_cast<int>(i) != *cmd.index) continue;
                    if (all && setting.lightFloat == nullptr && !state.scene.world.has<Shadow>(e)) continue;
                    writeSetting(state.scene.world, e, setting, cmd.number);
                }
                break;
            }
            case Verb::Debug:
                state.options.debugView = cmd.view;
                if (cmd.index) state.options.debugLight = *cmd.index;
                break;
            case Verb::ShadowMap:
                state.mapView.shown = cmd.index.has_value();
                state.mapView.light = cmd.index.value_or(0);
                state.mapView.layer = static_cast<int>(cmd.number);
                state.mapView.stale = true;
                break;
            case Verb::Camera:
                state.rig.reset(state.scene, state.scene.cameras[static_cast<std::size_t>(*cmd.index)]);
                break;
            case Verb::Exposure:
                state.autoExposure = !cmd.index;
                state.exposure = static_cast<float>(cmd.number);
                break;
            case Verb::Screenshot:
            case Verb::ScreenshotUi: {
                Status written = Ok{};
                if (cmd.verb == Verb::Screenshot) {
                    if (state.dirty) frameStep(app, false);
                    written = writeFrameScreenshot(state, cmd.path);
                } else {
                    // Dear ImGui hides a window on the frame it first appears in (while it
                    // measures it): one frame before the one captured.
                    frameStep(app, false);
                    frameStep(app, false, [&] { written = writeWindowScreenshot(state, cmd.path); });
                }
                if (!written) return fail(kExitFailure, cmd.path + ": " + written.error().message);
                break;
            }
            case Verb::Quit: return 0;
        }
        if (cmd.verb != Verb::Frames && cmd.verb != Verb::Dt && cmd.verb != Verb::Screenshot &&
            cmd.verb != Verb::ScreenshotUi) {
            state.dirty = true;
        }
    }
    return 0;
}

/// The script of --script FILE, or the one --frames/--screenshot stand for; empty when
/// interactive. The error names the file and line, or the flag.
Result<std::optional<std::vector<ScriptCommand>>> scriptOf(const Options& o, const Scene& scene) {
    const ScriptContext context{static_cast<int>(scene.lights.size()), static_cast<int>(scene.cameras.size())};
    if (!o.script.empty()) {
        auto text = readScriptFile(o.script);
        if (!text) return text.error();
        auto commands = parseScript(*text, o.script, context);
        if (!commands) return commands.error();
        return std::optional(std::move(*commands));
    }
    if (!o.frames && o.screenshotDir.empty()) return std::optional<std::vector<ScriptCommand>>{};
    std::ostringstream text;
    text << "dt " << o.dt << "\nframes " << o.frames.value_or(1) << "\n";
    if (!o.screenshotDir.empty()) {
        text << "screenshot " << o.screenshotDir << "/color.png\nscreenshot-ui " << o.screenshotDir
             << "/color_ui.png\n";
    }
    auto commands = parseScript(text.str(), "--frames/--screenshot", context);
    if (!commands) return commands.error();
    return std::optional(std::move(*commands));
}

/// Creates the folders the script's screenshots go to, after every check passed.
Status prepareScreenshotFolders(const std::vector<ScriptCommand>& commands, const std::string& scriptName) {
    for (const ScriptCommand& cmd : commands) {
        if (cmd.path.empty()) continue;
        const std::filesystem::path dir = std::filesystem::path(cmd.path).parent_path();
        if (dir.empty()) continue;
        if (Status s = samples::prepareOutputDir(dir.string()); !s) {
            return Error{ErrorCode::FileUnwritable, scriptName + ":" + std::to_string(cmd.line) + ": screenshot " +
                                                        cmd.path + ": " + s.error().message};
        }
    }
    return Ok{};
}

int run(const Options& o) {
    std::optional<std::pair<int, int>> size;
    if (o.size) {
        auto parsed = samples::parseSize(*o.size);
        if (!parsed) return fail(kExitBadInput, parsed.error().message);
        size = *parsed;
    }
    if (!std::isfinite(o.time) || o.time < 0.0) return fail(kExitBadInput, "--time: must be a finite number >= 0");
    if (!(std::isfinite(o.dt) && o.dt > 0.0)) return fail(kExitBadInput, "--dt: must be a finite number > 0");
    if (o.frames && (*o.frames < 1 || *o.frames > 100000))
        return fail(kExitBadInput, "--frames: must be in [1, 100000]");
    auto debug = parseDebugView(o.debug);
    if (!debug) return fail(kExitBadInput, "--debug: " + debug.error().message);
    const Result<ScreenVisibility> screenVisibility = samples::parseScreenVisibilitySetting(o.screenVisibility);
    if (!screenVisibility) return fail(kExitBadInput, "--screen-visibility: " + screenVisibility.error().message);
    std::optional<ShadowTechnique> technique;
    if (o.technique) {
        auto t = samples::parseTechnique(*o.technique);
        if (!t) return fail(kExitBadInput, "--technique: " + t.error().message);
        technique = *t;
    }

    App app;
    app.state.time = o.time;
    app.state.animation = o.animation;
    app.state.fixedSize = size;
    // The scene before the window, so that bad input costs no window (and needs no display).
    Result<Scene> probe = samples::loadSampleScene(o.scene, o.animation);
    if (!probe) return fail(kExitBadInput, probe.error().message);
    if (o.camera && (*o.camera < 0 || *o.camera >= static_cast<int>(probe->cameras.size()))) {
        return fail(kExitBadInput, "--camera " + std::to_string(*o.camera) + ": the scene has " +
                                       std::to_string(probe->cameras.size()) + " cameras");
    }
    // The lights the viewer will show, the default rig's among them, for --debug-light and scripts.
    if (Result<Entity> c = samples::chooseCameraAndRig(*probe, o.camera, o.time, o.rig, 16.0 / 9.0); !c)
        return fail(kExitBadInput, c.error().message);
    const int lights = static_cast<int>(probe->lights.size());
    if (o.debugLight < 0 || (lights > 0 && o.debugLight >= lights)) {
        return fail(kExitBadInput, "--debug-light " + std::to_string(o.debugLight) + ": the scene has " +
                                       std::to_string(lights) + " lights");
    }
    auto script = scriptOf(o, *probe);
    if (!script) return fail(kExitBadInput, script.error().message);
    const bool scripted = script->has_value();
    if (scripted) {
        if (Status s = prepareScreenshotFolders(**script, o.script.empty() ? "--screenshot" : o.script); !s)
            return fail(kExitBadInput, s.error().message);
    }

    const auto [width, height] = size.value_or(std::make_pair(1280, 720));
    auto window = createGlfwWindow(width, height, "shadow_viewer: " + o.scene);
    if (!window) return fail(kExitFailure, window.error().message);
    app.state.window = window->get();
    if (Status s = loadViewerGl((*window)->loader()); !s) return fail(kExitFailure, s.error().message);
    if (size) {
        RenderOptions sized;
        sized.width = width;
        sized.height = height;
        if (Status s = checkRenderSize(sized, lights); !s)
            return fail(kExitBadInput, "--size " + *o.size + ": " + s.error().message);
    }
    app.state.rigChoice = o.rig;
    if (Status s = loadInto(app.state, o.scene, o.camera); !s) return fail(kExitBadInput, s.error().message);
    if (technique) {
        app.state.scene.world.view<Shadow>().each([&](Entity, Shadow& s) {
            s.technique = *technique;
            s.autoTechnique = o.technique == kAutoTechniqueName;
        });
    }
    app.state.options.debugView = *debug;
    app.state.options.debugLight = o.debugLight;
    app.state.options.screenVisibility = *screenVisibility;

    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr;  // the layout is not saved: every run starts alike
    ImGui::StyleColorsDark();
    ImGui_ImplGlfw_InitForOpenGL(static_cast<GLFWwindow*>((*window)->nativeHandle()), true);
    ImGui_ImplOpenGL3_Init("#version 450 core");
    int code = 0;
    if (scripted) {
        code = runScript(app, **script);
    } else {
        while (!(*window)->shouldClose()) frameStep(app, true);
    }
    ImGui_ImplOpenGL3_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
    return code;
}

}  // namespace

int main(int argc, char** argv) {
    shadow::samples::keepFreedHeap();
    Options o;
    samples::CommandLine app{
        "Shows a scene with per-light shadows in a window, with panels to tune them; or runs a script."};
    app.add("scene", o.scene, "a .gltf/.glb file or builtin:NAME (default builtin:default)");
    app.add("--size", o.size, "render size WxH (default: the window's, 1280x720 at first)");
    app.add("--camera", o.camera, "index of the scene camera to start with (default: the first)");
    app.add("--time", o.time, "animation time to start at (s)");
    app.add("--animation", o.animation, samples::kAnimationHelp);
    app.add("--technique", o.technique,
            "override every shadowed light: " + techniqueNameList() + ", " + kAutoTechniqueName +
                " (chosen per light and frame, no budget)");
    app.add("--debug", o.debug, "debug view: none|cascade|blocker|penumbra|visibility|steps|closest");
    app.add("--debug-light", o.debugLight, "scene light index the debug view shows");
    app.add("--screen-visibility", o.screenVisibility, samples::kScreenVisibilityHelp);
    samples::addRigFlags(app, o.rig);
    auto script = app.add("--script", o.script, "run this script (docs/viewer.md) and exit");
    auto frames = app.add("--frames", o.frames, "render N frames from --time, then exit");
    app.add("--dt", o.dt, "time step between the frames of --frames (s)");
    auto screenshot = app.add("--screenshot", o.screenshotDir,
                              "after the frames of --frames (default 1), write DIR/color.png (the scene) and "
                              "DIR/color_ui.png (the window), then exit");
    script.excludes(frames);
    script.excludes(screenshot);
    if (const std::optional<int> exit = app.parse(argc, argv, "shadow_viewer")) return *exit;
    try {
        return run(o);
    } catch (const GlError& e) {
        return fail(kExitFailure, std::string("OpenGL: ") + e.what());
    } catch (const std::exception& e) {
        return fail(kExitFailure, e.what());
    }
}
