// The headless OSMesa backend (library shadow_osmesa, installed as the component
// shadow::osmesa: find_package(shadow_engine ... COMPONENTS osmesa)).
#pragma once

#include <shadow/context.h>
#include <shadow/result.h>

#include <memory>

namespace shadow {

/// A headless OSMesa OpenGL 4.5 core context, current and loaded on return.
[[nodiscard]] Result<std::unique_ptr<GlContext>> createOsMesaContext();

}  // namespace shadow
