// The few GL calls the viewer makes itself, besides the engine's and ImGui's: textures the UI
// draws (the tone-mapped frame, a shadow-map layer) and reading the window back for a
// screenshot with the UI. Entry points are resolved through the window's loader, as the engine
// resolves its own, so the viewer links no GL library.
#pragma once

#include <shadow/context.h>
#include <shadow/gl_handles.h>

#include <cstdint>
#include <vector>

namespace shadow::viewer {

/// Resolves the entry points below. Fails naming the first one missing.
[[nodiscard]] Status loadViewerGl(const GlProcLoader& loader);

/// An 8-bit RGB texture for `ImGui::Image`, reallocated when its size changes.
class UiTexture {
public:
    UiTexture() = default;
    ~UiTexture();
    UiTexture(const UiTexture&) = delete;
    UiTexture& operator=(const UiTexture&) = delete;

    /// Uploads `rgb` (width x height, rows top first, 3 bytes a pixel).
    void upload(int width, int height, const std::vector<std::uint8_t>& rgb);
    /// The texture as ImGui names it (ImTextureID), null before the first upload.
    [[nodiscard]] void* id() const;
    [[nodiscard]] int width() const { return width_; }
    [[nodiscard]] int height() const { return height_; }

private:
    unsigned name_ = 0;
    int width_ = 0;
    int height_ = 0;
};

/// `texture` as ImGui names a texture (ImTextureID).
[[nodiscard]] inline void* textureId(GlTexture texture) {
    return reinterpret_cast<void*>(static_cast<std::uintptr_t>(texture.name));
}

/// Clears the window's back buffer to dark grey (the margins around a frame of another aspect).
void clearWindow();

/// Reads the window's back buffer (what the next swap shows): width x height RGB, rows top first.
[[nodiscard]] std::vector<std::uint8_t> readWindowRgb(int width, int height);

}  // namespace shadow::viewer
