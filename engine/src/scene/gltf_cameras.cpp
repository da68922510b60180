#include "scene/gltf_cameras.h"

#include <cmath>
#include <glm/gtc/constants.hpp>

#include "scene/gltf_values.h"

namespace shadow::gltf {
namespace {

/// Far plane used for glTF's infinite projection (no `zfar`): 10 km.
constexpr double kInfiniteFar = 1e4;

}  // namespace

Result<Camera> importCamera(const tinygltf::Model& model, std::size_t index) {
    const tinygltf::Camera& camera = model.cameras[index];
    const std::string where = indexed("cameras", index);
    if (camera.type == "orthographic") {
        return elementError(where, "orthographic cameras are not supported", ErrorCode::Unsupported);
    }
    if (camera.type != "perspective") {
        return elementError(where + ".type", "unknown camera type \"" + camera.type + "\"");
    }
    const tinygltf::PerspectiveCamera& p = camera.perspective;
    const std::string pw = where + ".perspective";
    if (!(p.yfov > 0.0 && p.yfov < glm::pi<double>())) {
        return elementError(pw + ".yfov", "must be in (0, pi)");
    }
    if (!(p.znear > 0.0 && std::isfinite(p.znear))) {
        return elementError(pw + ".znear", "must be a positive number");
    }
    const double zfar = p.zfar == 0.0 ? kInfiniteFar : p.zfar;
    if (!(zfar > p.znear && std::isfinite(zfar))) {
        return elementError(pw + ".zfar",
                            p.zfar == 0.0 ? "absent, and znear is beyond 1e4 m" : "must be greater than znear");
    }
    if (!(p.aspectRatio >= 0.0 && std::isfinite(p.aspectRatio))) {
        return elementError(pw + ".aspectRatio", "must be a positive number");
    }
    return Camera{static_cast<float>(p.yfov), static_cast<float>(p.znear), static_cast<float>(zfar),
                  static_cast<float>(p.aspectRatio)};
}

}  // namespace shadow::gltf
