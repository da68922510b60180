// Windowed OpenGL through GLFW, for the viewer.
#include <GLFW/glfw3.h>

#include <shadow/window.h>

#include <array>
#include <utility>

namespace shadow {
namespace {

/// The keys that stand for `key` (GLFW_KEY_UNKNOWN when it has only one).
std::pair<int, int> glfwKeys(Window::Key key) {
    switch (key) {
        case Window::Key::Forward: return {GLFW_KEY_W, GLFW_KEY_UNKNOWN};
        case Window::Key::Back: return {GLFW_KEY_S, GLFW_KEY_UNKNOWN};
        case Window::Key::Left: return {GLFW_KEY_A, GLFW_KEY_UNKNOWN};
        case Window::Key::Right: return {GLFW_KEY_D, GLFW_KEY_UNKNOWN};
        case Window::Key::Up: return {GLFW_KEY_E, GLFW_KEY_UNKNOWN};
        case Window::Key::Down: return {GLFW_KEY_Q, GLFW_KEY_UNKNOWN};
        case Window::Key::NextTechnique: return {GLFW_KEY_T, GLFW_KEY_UNKNOWN};
        case Window::Key::Pause: return {GLFW_KEY_SPACE, GLFW_KEY_UNKNOWN};
        case Window::Key::Escape: return {GLFW_KEY_ESCAPE, GLFW_KEY_UNKNOWN};
        case Window::Key::Screenshot: return {GLFW_KEY_P, GLFW_KEY_UNKNOWN};
        case Window::Key::ToggleUi: return {GLFW_KEY_F1, GLFW_KEY_UNKNOWN};
        case Window::Key::CameraMode: return {GLFW_KEY_C, GLFW_KEY_UNKNOWN};
        case Window::Key::Fast: return {GLFW_KEY_LEFT_SHIFT, GLFW_KEY_RIGHT_SHIFT};
    }
    return {GLFW_KEY_UNKNOWN, GLFW_KEY_UNKNOWN};
}

int glfwButton(Window::Button button) {
    switch (button) {
        case Window::Button::Left: return GLFW_MOUSE_BUTTON_LEFT;
        case Window::Button::Right: return GLFW_MOUSE_BUTTON_RIGHT;
        case Window::Button::Middle: return GLFW_MOUSE_BUTTON_MIDDLE;
    }
    return GLFW_MOUSE_BUTTON_LEFT;
}

class GlfwWindow final : public Window {
public:
    /// Installs the scroll and drop callbacks, which reach this object through the window's user
    /// pointer (so the object must not move: it lives behind a unique_ptr).
    explicit GlfwWindow(GLFWwindow* window) : window_(window) {
        glfwSetWindowUserPointer(window_, this);
        glfwSetScrollCallback(window_, [](GLFWwindow* w, double, double dy) { self(w).scroll_ += dy; });
        glfwSetDropCallback(window_, [](GLFWwindow* w, int count, const char** paths) {
            for (int i = 0; i < count; ++i) self(w).dropped_.emplace_back(paths[i]);
        });
    }
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
    void requestClose() override { glfwSetWindowShouldClose(window_, GLFW_TRUE); }
    void swapBuffers() override { glfwSwapBuffers(window_); }
    void pollEvents() override { glfwPollEvents(); }
    void framebufferSize(int& width, int& height) const override { glfwGetFramebufferSize(window_, &width, &height); }
    [[nodiscard]] bool keyDown(Key key) const override {
        const auto [first, second] = glfwKeys(key);
        return glfwGetKey(window_, first) == GLFW_PRESS ||
               (second != GLFW_KEY_UNKNOWN && glfwGetKey(window_, second) == GLFW_PRESS);
    }
    [[nodiscard]] bool keyPressed(Key key) override {
        const auto i = static_cast<std::size_t>(key);
        const bool down = keyDown(key);
        const bool pressed = down && !wasDown_[i];
        wasDown_[i] = down;
        return pressed;
    }
    [[nodiscard]] bool buttonDown(Button button) const override {
        return glfwGetMouseButton(window_, glfwButton(button)) == GLFW_PRESS;
    }
    void cursorPosition(double& x, double& y) const override { glfwGetCursorPos(window_, &x, &y); }
    [[nodiscard]] double takeScroll() override { return std::exchange(scroll_, 0.0); }
    [[nodiscard]] std::vector<std::string> takeDroppedPaths() override { return std::exchange(dropped_, {}); }
    void setTitle(const std::string& title) override { glfwSetWindowTitle(window_, title.c_str()); }
    [[nodiscard]] void* nativeHandle() const override { return window_; }

private:
    static GlfwWindow& self(GLFWwindow* w) { return *static_cast<GlfwWindow*>(glfwGetWindowUserPointer(w)); }

    GLFWwindow* window_;
    std::array<bool, kKeyCount> wasDown_{};
    double scroll_ = 0.0;
    std::vector<std::string> dropped_;
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
