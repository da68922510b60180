// glTF cameras to engine `Camera`s. Perspective only: an orthographic camera is an error.
#pragma once

#include <shadow/components.h>
#include <shadow/result.h>
#include <tiny_gltf.h>

#include <cstddef>

namespace shadow::gltf {

/// `cameras[index]`, checked: yfov in (0, pi), znear > 0, zfar > znear. An absent `zfar`
/// (glTF's infinite projection) becomes 10 km.
[[nodiscard]] Result<Camera> importCamera(const tinygltf::Model& model, std::size_t index);

}  // namespace shadow::gltf
