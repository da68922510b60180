#include "viewer_camera.h"

#include <algorithm>
#include <cmath>

namespace shadow::viewer {
namespace {

constexpr double kTurnPerPixel = 0.005;  // rad
constexpr double kMaxPitch = 1.55;       // rad: just short of straight up or down

glm::dquat rotationOf(double yaw, double pitch) {
    return glm::angleAxis(yaw, glm::dvec3(0, 1, 0)) * glm::angleAxis(pitch, glm::dvec3(1, 0, 0));
}

DAabb sceneBounds(World& world) {
    DAabb bounds;
    world.view<WorldBounds>().each([&](Entity, WorldBounds& wb) { bounds.extend(wb.box); });
    if (bounds.empty()) {
        bounds.extend(glm::dvec3(-1.0));
        bounds.extend(glm::dvec3(1.0));
    }
    return bounds;
}

}  // namespace

void CameraRig::reset(Scene& scene, Entity sceneCamera) {
    sceneCamera_ = sceneCamera;
    mode_ = Mode::Scene;
    const DAabb bounds = sceneBounds(scene.world);
    sceneRadius_ = std::max(0.5 * glm::length(bounds.extent()), 1e-3);
    pivot_ = bounds.center();
    flySpeed_ = 0.5 * sceneRadius_;
    if (free_.isNull() || !scene.world.alive(free_)) {
        free_ = scene.world.create();
        scene.world.emplace<Name>(free_, Name{"viewer camera"});
        scene.world.emplace<Transform>(free_);
    }
    const Camera* own = scene.world.tryGet<Camera>(sceneCamera);
    scene.world.emplaceOrReplace<Camera>(free_, own != nullptr ? *own : Camera{});
}

void CameraRig::setMode(World& world, Mode mode) {
    if (mode != Mode::Scene && mode_ == Mode::Scene) takeOverPose(world);
    mode_ = mode;
    if (mode_ != Mode::Scene) writePose(world);
}

void CameraRig::takeOverPose(World& world) {
    const WorldTransform* wt = world.tryGet<WorldTransform>(sceneCamera_);
    if (wt == nullptr) return;
    position_ = glm::dvec3(wt->worldFromLocal[3]);
    const glm::dvec3 forward = -worldOrientation(*wt)[2];
    yaw_ = std::atan2(-forward.x, -forward.z);
    pitch_ = std::asin(std::clamp(forward.y, -1.0, 1.0));
    // The pivot: the point on the view ray nearest the scene's centre, at least a tenth of the
    // scene's radius ahead.
    distance_ = std::max(glm::dot(pivot_ - position_, forward), 0.1 * sceneRadius_);
    pivot_ = position_ + forward * distance_;
}

void CameraRig::writePose(World& world) const {
    Transform& t = world.get<Transform>(free_);
    t.translation = position_;
    t.rotation = rotationOf(yaw_, pitch_);
    t.scale = glm::dvec3(1.0);
    // The far plane follows the camera out, so that zooming out never clips the scene.
    Camera& c = world.get<Camera>(free_);
    c.zfar = std::max(c.zfar, static_cast<float>(1.5 * (glm::length(position_ - pivot_) + 2.0 * sceneRadius_)));
}

void CameraRig::update(World& world, const CameraInput& in) {
    const bool moves = in.turn || in.zoom || in.pan || in.scroll != 0.0 || in.fly != glm::dvec3(0.0);
    if (!moves) return;
    if (mode_ == Mode::Scene) setMode(world, in.fly != glm::dvec3(0.0) ? Mode::Fly : Mode::Orbit);
    const glm::dmat3 axes = glm::mat3_cast(rotationOf(yaw_, pitch_));
    if (in.turn) {
        yaw_ -= in.dx * kTurnPerPixel;
        pitch_ = std::clamp(pitch_ - in.dy * kTurnPerPixel, -kMaxPitch, kMaxPitch);
    }
    if (mode_ == Mode::Orbit) {
        if (in.zoom) distance_ *= std::exp(in.dy * 0.01);
        distance_ *= std::pow(0.85, in.scroll);
        distance_ = std::clamp(distance_, 1e-3 * sceneRadius_, 100.0 * sceneRadius_);
        if (in.pan) pivot_ += (-axes[0] * in.dx + axes[1] * in.dy) * (distance_ * 0.0015);
        const glm::dvec3 forward = -glm::mat3_cast(rotationOf(yaw_, pitch_))[2];
        position_ = pivot_ - forward * distance_;
    } else {
        flySpeed_ *= std::pow(1.25, in.scroll);
        const double speed = flySpeed_ * (in.fast ? 4.0 : 1.0) * in.dt;
        position_ += (axes[0] * in.fly.x + glm::dvec3(0, 1, 0) * in.fly.y - axes[2] * in.fly.z) * speed;
        // Keep the pivot ahead, so that switching to orbit turns about what is in view.
        pivot_ = position_ - glm::mat3_cast(rotationOf(yaw_, pitch_))[2] * distance_;
    }
    writePose(world);
}

}  // namespace shadow::viewer
