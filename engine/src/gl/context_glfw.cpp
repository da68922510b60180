// Windowed OpenGL through GLFW, for the viewer.
#include <GLFW/glfw3.h>

#include <shadow/window.h>

#include <array>

namespace shadow {
namespace {

int glfwKey(Window::Key key) {
    switch (key) {
        case Window::Key::Forward: return GLFW_KEY_W;
        case Window::Key::Back: return GLFW_KEY_S;
        case Window::Key::Left: return GLFW_KEY_A;
        case Window::Key::Right: return GLFW_KEY_D;
        case Window::Key::Up: return GLFW_KEY_E;
        case Window::Key::Down: return GLFW_KEY_Q;
        case Window::Key::NextTechnique: return GLFW_KEY_T;
        case Window::Key::Pause: return GLFW_KEY_SPACE;
        case Window::Key::Escape: return GLFW_KEY_ESCAPE;
    }
    return GLFW_KEY_UNKNOWN;
}

class GlfwWindow final : public Window {
public:
    explicit GlfwWindow(GLFWwindow* window) : window_(window) {}
    ~GlfwWindow() override {
        glfwDestroyWindow(window_);
        glfwTerminate();
    }
    GlfwWindow(const GlfwWindow&) = delete;
    GlfwWindow& operator=(const GlfwWindow&) = delete;

    void makeCurrent() override { glfwMakeContextCurrent(window_); }
    [[nodiscard]] GlProcLoader loader() const override {
        return [](const char* name) { return reinterpret_cast<void*>(glfwGetProcAddress(name)); };
    }
    [[nodiscard]] const char* backend() const override { return "glfw"; }
    [[nodiscard]] bool shouldClose() const override { return glfwWindowShouldClose(window_) != 0; }
    void swapBuffers() override { glfwSwapBuffers(window_); }
    void pollEvents() override { glfwPollEvents(); }
    void framebufferSize(int& width, int& height) const override { glfwGetFramebufferSize(window_, &width, &height); }
    [[nodiscard]] bool keyDown(Key key) const override { return glfwGetKey(window_, glfwKey(key)) == GLFW_PRESS; }
    [[nodiscard]] bool keyPressed(Key key) override {
        const auto i = static_cast<std::size_t>(key);
        const bool down = keyDown(key);
        const bool pressed = down && !wasDown_[i];
        wasDown_[i] = down;
        return pressed;
    }

private:
    GLFWwindow* window_;
    std::array<bool, 9> wasDown_{};
};

}  // namespace

Result<std::unique_ptr<Window>> createGlfwWindow(int width, int height, const std::string& title) {
    if (glfwInit() != GLFW_TRUE) return Error{ErrorCode::GlUnavailable, "GLFW: initialisation failed (no display?)"};
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    GLFWwindow* raw = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
    if (raw == nullptr) {
        glfwTerminate();
        return Error{ErrorCode::GlUnavailable, "GLFW: could not open a window with an OpenGL 4.5 core context"};
    }
    auto window = std::make_unique<GlfwWindow>(raw);
    window->makeCurrent();
    glfwSwapInterval(1);
    if (Status s = loadGl(window->loader()); !s) return s.error();
    return std::unique_ptr<Window>(std::move(window));
}

}  // namespace shadow
