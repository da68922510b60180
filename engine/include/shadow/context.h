// OpenGL contexts and loading the engine's GL function table.
//
// A game that owns its context calls `loadGl` once with its own getProcAddress after making the
// context current (OpenGL 4.5 core). The samples use one of the backends below, each in its
// own library with its own header, so that a binary links exactly one GL provider (libOSMesa
// and libGL must not share a process) and a header is installed only with the library that
// defines what it declares:
//   shadow_osmesa  headless, software (Mesa llvmpipe); the default of the samples and tests
//                  (shadow/context_osmesa.h; installed as the component shadow::osmesa)
//   shadow_glfw    a window (the viewer; shadow/window.h; not installed)
//   shadow_egl     headless on a GPU through EGL (optional; shadow/context_egl.h; not installed)
#pragma once

#include <shadow/result.h>

#include <functional>
#include <memory>
#include <stdexcept>
#include <string>

namespace shadow {

/// A GL error, a shader that failed to compile or link (naming the shader file and line), or an
/// incomplete framebuffer. Thrown by GL-side calls; the samples turn it into a message.
class GlError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// The `GlError` of a call made before `loadGl` (no OpenGL to call): what the calls returning an
/// error value report as `ErrorCode::GlUnavailable`.
class GlNotLoaded : public GlError {
public:
    using GlError::GlError;
};

/// Resolves one GL entry point by name; returns null when the context lacks it.
using GlProcLoader = std::function<void*(const char* name)>;

/// Fills the engine's GL table from `loader`. Fails naming the first missing entry point, or
/// when the current context is older than OpenGL 4.5.
[[nodiscard]] Status loadGl(const GlProcLoader& loader);

/// Facts about the current context, read after `loadGl`.
struct GlInfo {
    std::string vendor;
    std::string renderer;  ///< GL_RENDERER, named next to every timing
    std::string version;
    int maxTextureSize = 0;
    int maxArrayLayers = 0;
    int maxTextureUnits = 0;  ///< fragment-shader texture image units
    /// True for CPU rasterisers (llvmpipe, softpipe, swrast), where timer queries do not
    /// measure rasterisation and passes are timed by wall clock between fences.
    bool softwareRenderer = false;
};

/// Queries `GlInfo` from the current context. Requires `loadGl`.
[[nodiscard]] GlInfo queryGlInfo();

/// An OpenGL context owned by one of the backends.
class GlContext {
public:
    virtual ~GlContext() = default;
    /// Makes the context current on the calling thread.
    virtual void makeCurrent() = 0;
    /// Resolves entry points of this context (pass to `loadGl`).
    [[nodiscard]] virtual GlProcLoader loader() const = 0;
    /// Which backend made it ("osmesa", "glfw", "egl").
    [[nodiscard]] virtual const char* backend() const = 0;
};

}  // namespace shadow
