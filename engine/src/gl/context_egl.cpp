// Headless OpenGL through EGL, for machines with a GPU: a 1x1 pbuffer surface keeps the
// context current; the engine renders into its own framebuffers.
#include <EGL/egl.h>

#include <shadow/context_egl.h>

#include <cstdio>
#include <memory>
#include <string>

namespace shadow {
namespace {

class EglContext final : public GlContext {
public:
    EglContext(EGLDisplay display, EGLContext context, EGLSurface surface)
        : display_(display), context_(context), surface_(surface) {}
    ~EglContext() override {
        eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        eglDestroySurface(display_, surface_);
        eglDestroyContext(display_, context_);
        eglTerminate(display_);
    }
    EglContext(const EglContext&) = delete;
    EglContext& operator=(const EglContext&) = delete;

    void makeCurrent() override { eglMakeCurrent(display_, surface_, surface_, context_); }
    [[nodiscard]] GlProcLoader loader() const override {
        return [](const char* name) { return reinterpret_cast<void*>(eglGetProcAddress(name)); };
    }
    [[nodiscard]] const char* backend() const override { return "egl"; }

private:
    EGLDisplay display_;
    EGLContext context_;
    EGLSurface surface_;
};

Error eglError(const std::string& what) {
    return Error{ErrorCode::GlUnavailable, "EGL: " + what + " failed (error 0x" + [] {
                     char buf[16];
                     std::snprintf(buf, sizeof(buf), "%04x", static_cast<unsigned>(eglGetError()));
                     return std::string(buf);
                 }() + ")"};
}

}  // namespace

Result<std::unique_ptr<GlContext>> createEglContext() {
    EGLDisplay display = eglGetDisplay(EGL_DEFAULT_DISPLAY);
    if (display == EGL_NO_DISPLAY) return Error{ErrorCode::GlUnavailable, "EGL: no display"};
    if (eglInitialize(display, nullptr, nullptr) != EGL_TRUE) return eglError("eglInitialize");
    if (eglBindAPI(EGL_OPENGL_API) != EGL_TRUE) {
        eglTerminate(display);
        return eglError("eglBindAPI(OpenGL)");
    }
    const EGLint configAttribs[] = {
        EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_RED_SIZE, 8, EGL_NONE};
    EGLConfig config = nullptr;
    EGLint count = 0;
    if (eglChooseConfig(display, configAttribs, &config, 1, &count) != EGL_TRUE || count < 1) {
        eglTerminate(display);
        return eglError("eglChooseConfig");
    }
    const EGLint contextAttribs[] = {
        EGL_CONTEXT_MAJOR_VERSION,           4,       EGL_CONTEXT_MINOR_VERSION, 5, EGL_CONTEXT_OPENGL_PROFILE_MASK,
        EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
    EGLContext context = eglCreateContext(display, config, EGL_NO_CONTEXT, contextAttribs);
    if (context == EGL_NO_CONTEXT) {
        eglTerminate(display);
        return eglError("eglCreateContext(OpenGL 4.5 core)");
    }
    const EGLint surfaceAttribs[] = {EGL_WIDTH, 1, EGL_HEIGHT, 1, EGL_NONE};
    EGLSurface surface = eglCreatePbufferSurface(display, config, surfaceAttribs);
    if (surface == EGL_NO_SURFACE) {
        eglDestroyContext(display, context);
        eglTerminate(display);
        return eglError("eglCreatePbufferSurface");
    }
    auto ctx = std::make_unique<EglContext>(display, context, surface);
    ctx->makeCurrent();
    if (Status s = loadGl(ctx->loader()); !s) return s.error();
    return std::unique_ptr<GlContext>(std::move(ctx));
}

}  // namespace shadow
