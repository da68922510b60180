// shadow_viewer: the animated scenes in a window.
//
//   shadow_viewer [SCENE]        SCENE: .gltf/.glb or builtin:NAME (default builtin:default)
//
// W/A/S/D/Q/E move the camera, T cycles every light's technique (scene's own, hard, PCF, PCSS),
// Space pauses the animation, Esc quits. Per-pass timings are printed once a second.
#include <shadow/frame_runner.h>
#include <shadow/scene.h>
#include <shadow/window.h>

#include "render_output.h"

#include <chrono>
#include <iostream>
#include <map>

namespace {

using namespace shadow;

void moveCamera(Window& window, World& world, Entity camera, double dt) {
    Transform* t = world.tryGet<Transform>(camera);
    if (t == nullptr) return;
    const glm::dmat3 axes = glm::mat3_cast(t->rotation);
    glm::dvec3 move(0.0);
    if (window.keyDown(Window::Key::Forward)) move -= axes[2];
    if (window.keyDown(Window::Key::Back)) move += axes[2];
    if (window.keyDown(Window::Key::Left)) move -= axes[0];
    if (window.keyDown(Window::Key::Right)) move += axes[0];
    if (window.keyDown(Window::Key::Up)) move += glm::dvec3(0, 1, 0);
    if (window.keyDown(Window::Key::Down)) move -= glm::dvec3(0, 1, 0);
    t->translation += move * (4.0 * dt);
}

}  // namespace

int main(int argc, char** argv) {
    const std::string spec = argc > 1 ? argv[1] : "builtin:default";
    Result<Scene> loaded = loadScene(spec);
    if (!loaded) {
        std::cerr << "shadow_viewer: " << loaded.error().message << "\n";
        return 2;
    }
    Scene& scene = *loaded;
    auto window = createGlfwWindow(1280, 720, "shadow_viewer: " + spec);
    if (!window) {
        std::cerr << "shadow_viewer: " << window.error().message << "\n";
        return 1;
    }
    Entity camera;
    if (scene.cameras.empty()) {
        (void)updateTransforms(scene.world);
        camera = addDefaultCamera(scene);
    } else {
        camera = scene.cameras.front();
    }
    // The scene's own techniques, to restore when cycling back.
    std::map<std::uint32_t, ShadowTechnique> own;
    scene.world.view<Shadow>().each([&](Entity e, Shadow& s) { own[e.bits()] = s.technique; });
    int techniqueMode = 0;  // 0 = own, then hard, pcf, pcss

    try {
        FrameRunner runner;
        FrameStats stats;  // kept: a frame that reuses it allocates nothing in steady state
        double t = 0.0;
        bool paused = false;
        auto last = std::chrono::steady_clock::now();
        auto lastReport = last;
        while (!(*window)->shouldClose() && !(*window)->keyDown(Window::Key::Escape)) {
            (*window)->pollEvents();
            const auto now = std::chrono::steady_clock::now();
            const double dt = std::chrono::duration<double>(now - last).count();
            last = now;
            if ((*window)->keyPressed(Window::Key::Pause)) paused = !paused;
            if ((*window)->keyPressed(Window::Key::NextTechnique)) {
                techniqueMode = (techniqueMode + 1) % 4;
                const ShadowTechnique forced[] = {ShadowTechnique::Hard, ShadowTechnique::Hard, ShadowTechnique::Pcf,
                                                  ShadowTechnique::Pcss};
                scene.world.view<Shadow>().each([&](Entity e, Shadow& s) {
                    s.technique = techniqueMode == 0 ? own[e.bits()] : forced[techniqueMode];
                });
                std::cout << "technique: "
                          << (techniqueMode == 0 ? "scene's own" : techniqueName(forced[techniqueMode])) << "\n";
            }
            if (!paused) t += dt;
            moveCamera(**window, scene.world, camera, dt);
            RenderOptions options;
            (*window)->framebufferSize(options.width, options.height);
            if (options.width < 1 || options.height < 1) continue;
            runner.runFrame(scene, t, camera, options, stats);
            runner.renderer().present(options.width, options.height);
            (*window)->swapBuffers();
            if (std::chrono::duration<double>(now - lastReport).count() > 1.0) {
                lastReport = now;
                std::cout << "shadow " << stats.passMs("Shadow/") << " ms, main " << stats.passMs("Main/")
                          << " ms, layers drawn " << stats.shadowLayersDrawn << " reused " << stats.shadowLayersReused
                          << " (" << stats.renderer << ")\n";
            }
        }
    } catch (const std::exception& e) {
        std::cerr << "shadow_viewer: " << e.what() << "\n";
        return 1;
    }
    return 0;
}
