#include "viewer_gl.h"

#include <GL/glcorearb.h>

#include <algorithm>
#include <string>

namespace shadow::viewer {
namespace {

#define VIEWER_GL_FUNCTIONS(X)                                         \
    X(PFNGLCREATETEXTURESPROC, CreateTextures)                         \
    X(PFNGLDELETETEXTURESPROC, DeleteTextures)                         \
    X(PFNGLTEXTURESTORAGE2DPROC, TextureStorage2D)                     \
    X(PFNGLTEXTURESUBIMAGE2DPROC, TextureSubImage2D)                   \
    X(PFNGLTEXTUREPARAMETERIPROC, TextureParameteri)                   \
    X(PFNGLPIXELSTOREIPROC, PixelStorei)                               \
    X(PFNGLBINDFRAMEBUFFERPROC, BindFramebuffer)                       \
    X(PFNGLBINDBUFFERPROC, BindBuffer)                                 \
    X(PFNGLNAMEDFRAMEBUFFERREADBUFFERPROC, NamedFramebufferReadBuffer) \
    X(PFNGLREADPIXELSPROC, ReadPixels)                                 \
    X(PFNGLCLEARNAMEDFRAMEBUFFERFVPROC, ClearNamedFramebufferfv)

struct Table {
#define VIEWER_GL_MEMBER(type, name) type name = nullptr;
    VIEWER_GL_FUNCTIONS(VIEWER_GL_MEMBER)
#undef VIEWER_GL_MEMBER
};
Table gl;

/// Pixel rows tightly packed, no pixel buffer bound: what the uploads and reads below assume.
void tightRows() {
    gl.PixelStorei(GL_UNPACK_ALIGNMENT, 1);
    gl.PixelStorei(GL_UNPACK_ROW_LENGTH, 0);
    gl.PixelStorei(GL_PACK_ALIGNMENT, 1);
    gl.PixelStorei(GL_PACK_ROW_LENGTH, 0);
    gl.BindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
    gl.BindBuffer(GL_PIXEL_PACK_BUFFER, 0);
}

}  // namespace

Status loadViewerGl(const GlProcLoader& loader) {
#define VIEWER_GL_LOAD(type, name)                                                           \
    gl.name = reinterpret_cast<type>(loader("gl" #name));                                    \
    if (gl.name == nullptr) {                                                                \
        return Error{ErrorCode::GlUnavailable, std::string("the context lacks gl") + #name}; \
    }
    VIEWER_GL_FUNCTIONS(VIEWER_GL_LOAD)
#undef VIEWER_GL_LOAD
    return Ok{};
}

UiTexture::~UiTexture() {
    if (name_ != 0) gl.DeleteTextures(1, &name_);
}

void UiTexture::upload(int width, int height, const std::vector<std::uint8_t>& rgb) {
    if (width != width_ || height != height_ || name_ == 0) {
        if (name_ != 0) gl.DeleteTextures(1, &name_);
        gl.CreateTextures(GL_TEXTURE_2D, 1, &name_);
        gl.TextureStorage2D(name_, 1, GL_RGB8, width, height);
        gl.TextureParameteri(name_, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
        gl.TextureParameteri(name_, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        gl.TextureParameteri(name_, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        gl.TextureParameteri(name_, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
        width_ = width;
        height_ = height;
    }
    tightRows();
    gl.TextureSubImage2D(name_, 0, 0, 0, width, height, GL_RGB, GL_UNSIGNED_BYTE, rgb.data());
}

void* UiTexture::id() const { return reinterpret_cast<void*>(static_cast<std::uintptr_t>(name_)); }

void clearWindow() {
    const float grey[4] = {0.1f, 0.1f, 0.1f, 1.0f};
    gl.ClearNamedFramebufferfv(0, GL_COLOR, 0, grey);
}

std::vector<std::uint8_t> readWindowRgb(int width, int height) {
    const std::size_t row = static_cast<std::size_t>(width) * 3;
    std::vector<std::uint8_t> raw(row * static_cast<std::size_t>(height));
    gl.BindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    gl.NamedFramebufferReadBuffer(0, GL_BACK);
    tightRows();
    gl.ReadPixels(0, 0, width, height, GL_RGB, GL_UNSIGNED_BYTE, raw.data());
    // GL rows start at the bottom; images at the top.
    std::vector<std::uint8_t> out(raw.size());
    for (int y = 0; y < height; ++y) {
        std::copy_n(raw.begin() + static_cast<std::ptrdiff_t>(row * static_cast<std::size_t>(height - 1 - y)), row,
                    out.begin() + static_cast<std::ptrdiff_t>(row * static_cast<std::size_t>(y)));
    }
    return out;
}

}  // namespace shadow::viewer
