// A window with an OpenGL 4.5 core context, for the viewer (link `shadow_glfw`).
#pragma once

#include <shadow/context.h>

#include <memory>
#include <string>

namespace shadow {

/// A GLFW window whose context is current and loaded.
class Window : public GlContext {
public:
    /// Keys the viewer reads.
    enum class Key { Forward, Back, Left, Right, Up, Down, NextTechnique, Pause, Escape };

    [[nodiscard]] virtual bool shouldClose() const = 0;
    virtual void swapBuffers() = 0;
    virtual void pollEvents() = 0;
    /// Framebuffer size in pixels.
    virtual void framebufferSize(int& width, int& height) const = 0;
    [[nodiscard]] virtual bool keyDown(Key key) const = 0;
    /// True once per press.
    [[nodiscard]] virtual bool keyPressed(Key key) = 0;
};

/// Opens a window of `width` x `height` with an OpenGL 4.5 core context.
[[nodiscard]] Result<std::unique_ptr<Window>> createGlfwWindow(int width, int height, const std::string& title);

}  // namespace shadow
