// A window with an OpenGL 4.5 core context, for the viewer (link `shadow_glfw`).
//
// The events a viewer reads without knowing GLFW: keys by intent, the mouse, the scroll wheel and
// files dropped on the window. A UI library that needs the native window (Dear ImGui's GLFW
// backend) takes `nativeHandle()`; it may install its own callbacks after the window's, which it
// must chain (ImGui's backend does), so that scrolling and dropping still reach the window.
#pragma once

#include <shadow/context.h>

#include <memory>
#include <string>
#include <vector>

namespace shadow {

/// A GLFW window whose context is current and loaded.
class Window : public GlContext {
public:
    /// Keys the viewer reads, by intent (context_glfw.cpp maps them to keys).
    enum class Key {
        Forward,        ///< W
        Back,           ///< S
        Left,           ///< A
        Right,          ///< D
        Up,             ///< E
        Down,           ///< Q
        NextTechnique,  ///< T
        Pause,          ///< Space
        Escape,         ///< Esc
        Screenshot,     ///< P
        ToggleUi,       ///< F1
        CameraMode,     ///< C
        Fast,           ///< either Shift
    };
    /// Number of `Key` values.
    static constexpr int kKeyCount = static_cast<int>(Key::Fast) + 1;
    /// Mouse buttons.
    enum class Button { Left, Right, Middle };

    [[nodiscard]] virtual bool shouldClose() const = 0;
    /// Asks the loop to end (`shouldClose` turns true).
    virtual void requestClose() = 0;
    virtual void swapBuffers() = 0;
    virtual void pollEvents() = 0;
    /// Framebuffer size in pixels.
    virtual void framebufferSize(int& width, int& height) const = 0;
    [[nodiscard]] virtual bool keyDown(Key key) const = 0;
    /// True once per press.
    [[nodiscard]] virtual bool keyPressed(Key key) = 0;
    [[nodiscard]] virtual bool buttonDown(Button button) const = 0;
    /// Cursor position in window coordinates (pixels of the window, origin top-left).
    virtual void cursorPosition(double& x, double& y) const = 0;
    /// Vertical scroll (wheel notches, up positive) since the last call.
    [[nodiscard]] virtual double takeScroll() = 0;
    /// Paths of the files dropped on the window since the last call, in the order dropped.
    [[nodiscard]] virtual std::vector<std::string> takeDroppedPaths() = 0;
    /// Sets the title bar's text.
    virtual void setTitle(const std::string& title) = 0;
    /// The native window (a `GLFWwindow*`), for UI libraries with a GLFW backend.
    [[nodiscard]] virtual void* nativeHandle() const = 0;
};

/// Opens a window of `width` x `height` with an OpenGL 4.5 core context.
[[nodiscard]] Result<std::unique_ptr<Window>> createGlfwWindow(int width, int height, const std::string& title);

}  // namespace shadow
