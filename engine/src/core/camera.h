// The camera's projection, shared by the decide phase (light culling), the renderer's passes and
// the shadow mask. Pure CPU, in double precision.
#pragma once

#include <shadow/scene.h>

#include <glm/glm.hpp>

namespace shadow {

/// The camera's projection (view -> clip, GL's [-1, 1] depth), in double.
glm::dmat4 cameraClipFromView(const CameraView& camera);
/// The camera's clip-from-world matrix in double (absolute world space).
glm::dmat4 cameraClipFromWorld(const CameraView& camera);
/// `clipFromView` times the camera's view, made to take camera-relative positions (world minus
/// the camera's position): what the main pass and the shadow mask draw with, float-precise far
/// from the origin.
glm::dmat4 cameraClipFromCs(const CameraView& camera, const glm::dmat4& clipFromView);
/// The unit direction the camera looks along (its view's -Z), in world space.
glm::vec3 cameraForward(const CameraView& camera);

}  // namespace shadow
