#include "core/camera.h"

#include <glm/gtc/matrix_transform.hpp>

namespace shadow {

glm::dmat4 cameraClipFromView(const CameraView& camera) {
    return glm::perspective(static_cast<double>(camera.yfov), static_cast<double>(camera.aspect),
                            static_cast<double>(camera.znear), static_cast<double>(camera.zfar));
}

glm::dmat4 cameraClipFromWorld(const CameraView& camera) { return cameraClipFromView(camera) * camera.viewFromWorld; }

glm::dmat4 cameraClipFromCs(const CameraView& camera, const glm::dmat4& clipFromView) {
    return clipFromView * (camera.viewFromWorld * glm::translate(glm::dmat4(1.0), camera.wsPosition));
}

glm::vec3 cameraForward(const CameraView& camera) {
    return glm::normalize(glm::vec3(-glm::dvec3(glm::transpose(camera.viewFromWorld)[2])));
}

}  // namespace shadow
