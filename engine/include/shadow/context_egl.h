// The headless EGL backend (library shadow_egl, built with SHADOW_WITH_EGL; serves the samples
// on machines with a GPU and is not installed).
#pragma once

#include <shadow/context.h>
#include <shadow/result.h>

#include <memory>

namespace shadow {

/// A headless EGL (surfaceless/pbuffer) OpenGL 4.5 core context, current and loaded on return.
[[nodiscard]] Result<std::unique_ptr<GlContext>> createEglContext();

}  // namespace shadow
