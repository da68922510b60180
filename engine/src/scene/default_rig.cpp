// The default rig (shadow/default_rig.h): a sun and a ground placed from the model's bounds.
#include <shadow/default_rig.h>

#include "scene/default_camera.h"

#include <glm/gtc/constants.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace shadow {
namespace {

constexpr double kDegree = glm::pi<double>() / 180.0;
/// The ground lies this fraction of the model's size below the bounds' lowest point: close enough
/// for the model to stand on it, far enough that a flat base of the model does not fight it.
constexpr double kGroundGap = 1e-3;
/// The ground's half-edge is at least this many times the model's largest edge.
constexpr double kGroundHalfMin = 2.0;
/// Added to the reach of the model's shadow on the ground, as a fraction of the model's size.
constexpr double kGroundBorder = 0.25;
/// The camera added frames the model and its shadow with this margin.
constexpr double kFramingMargin = 1.05;
/// The most poses `DefaultRigOptions::boundsSamples` may ask for.
constexpr int kMaxBoundsSamples = 256;

/// Options clamped to their documented ranges (NaN to the default).
DefaultRigOptions clamped(DefaultRigOptions o) {
    const DefaultRigOptions d;
    auto clamp = [](auto v, auto lo, auto hi, auto fallback) {
        return std::isnan(v) ? fallback : std::clamp(v, lo, hi);
    };
    o.sunElevation = clamp(o.sunElevation, 10.0 * kDegree, 90.0 * kDegree, d.sunElevation);
    o.sunAzimuth = clamp(o.sunAzimuth, -glm::pi<double>(), glm::pi<double>(), d.sunAzimuth);
    o.angularRadius = clamp(o.angularRadius, 0.0f, 0.2f, d.angularRadius);
    o.intensity = clamp(o.intensity, 0.0f, 1e12f, d.intensity);
    o.mapSize = std::clamp(o.mapSize, 1, 16384);
    o.boundsMargin = clamp(o.boundsMargin, 0.0, 1.0, d.boundsMargin);
    o.imageAspect = clamp(o.imageAspect, 0.1, 10.0, d.imageAspect);
    if (!std::isfinite(o.boundsTime)) o.boundsTime = 0.0;
    o.boundsSamples = std::clamp(o.boundsSamples, 1, kMaxBoundsSamples);
    return o;
}

/// The camera's forward flattened onto the ground (unit); its up vector's when it looks straight
/// down or up, -Z when it has no pose.
glm::dvec3 horizontalForward(const World& world, Entity camera) {
    const WorldTransform* wt = world.tryGet<WorldTransform>(camera);
    if (wt == nullptr || !wt->finite) return {0.0, 0.0, -1.0};
    const glm::dmat3 axes = worldOrientation(*wt);
    for (const glm::dvec3& v : {-axes[2], axes[1]}) {
        const glm::dvec3 flat(v.x, 0.0, v.z);
        if (glm::length(flat) > 1e-3) return glm::normalize(flat);
    }
    return {0.0, 0.0, -1.0};
}

/// The direction the sun's light travels, from the camera's horizontal forward `forward`.
glm::dvec3 sunDirection(const glm::dvec3& forward, const DefaultRigOptions& o) {
    const glm::dvec3 right = glm::cross(forward, glm::dvec3(0.0, 1.0, 0.0));
    const glm::dvec3 along = std::cos(o.sunAzimuth) * forward + std::sin(o.sunAzimuth) * right;
    return glm::normalize(std::cos(o.sunElevation) * along - glm::dvec3(0.0, std::sin(o.sunElevation), 0.0));
}

/// The bounds' eight corners and where each one's shadow falls on the plane y = `groundY`.
std::vector<glm::dvec3> modelAndShadowPoints(const DAabb& bounds, const glm::dvec3& sun, double groundY) {
    std::vector<glm::dvec3> points;
    for (int c = 0; c < 8; ++c) {
        const glm::dvec3 p = bounds.corner(c);
        points.push_back(p);
        points.push_back(p + sun * ((p.y - groundY) / -sun.y));  // sun.y <= -sin(10 degrees)
    }
    return points;
}

/// Adds a camera looking along `view` at `points`, at the nearest distance that holds them all
/// inside its field of view in an image of width / height `aspect`; its far plane reaches
/// `farthest` too.
Entity addFramingCamera(Scene& scene, const std::vector<glm::dvec3>& points, const glm::dvec3& view,
                        const std::array<glm::dvec3, 4>& farthest, double aspect) {
    DAabb box;
    for (const glm::dvec3& p : points) box.extend(p);
    const glm::dvec3 target = box.center();
    const glm::dvec3 right = glm::normalize(glm::cross(view, glm::dvec3(0.0, 1.0, 0.0)));
    const glm::dvec3 up = glm::cross(right, view);
    Camera camera;
    const double tanHalf = std::tan(0.5 * camera.yfov);
    double distance = 0.0;
    for (const glm::dvec3& p : points) {
        const glm::dvec3 q = p - target;
        const double across = std::max(std::abs(glm::dot(q, right)) / aspect, std::abs(glm::dot(q, up)));
        distance = std::max(distance, across / tanHalf - glm::dot(q, view));
    }
    distance = std::max(distance * kFramingMargin, 1e-3 * glm::length(box.extent()) + 1e-6);
    const glm::dvec3 eye = target - distance * view;
    double nearest = distance, farDepth = 0.0;
    for (const glm::dvec3& p : points) nearest = std::min(nearest, glm::dot(p - eye, view));
    for (const glm::dvec3& p : farthest) farDepth = std::max(farDepth, glm::dot(p - eye, view));
    camera.znear = static_cast<float>(std::max(0.5 * nearest, 1e-3 * distance));
    camera.zfar = static_cast<float>(std::max(1.5 * std::max(farDepth, distance), 2.0 * camera.znear));
    return addCamera(scene, "default camera", camera, eye, target);
}

/// The ground: a square at `y` under the model's centre, receiving only.
Entity addGround(Scene& scene, const glm::dvec3& center, double y, double halfSize) {
    Transform at;
    at.translation = {center.x, y, center.z};
    Material grey;
    grey.albedo = glm::vec3(0.5f);
    const Entity ground =
        addMeshInstance(scene.world, "default ground", makePlaneMesh(static_cast<float>(halfSize)), at, grey);
    scene.world.get<Mesh>(ground).castShadows = false;
    return ground;
}

/// The sun, shining along `direction`, placed (for show: a sun has no position) above the model.
Entity addSun(Scene& scene, const glm::dvec3& center, double size, const glm::dvec3& direction,
              const DefaultRigOptions& o) {
    Light light;
    light.type = LightType::Directional;
    light.color = o.color;
    light.intensity = o.intensity;
    light.angularRadius = o.angularRadius;
    Shadow shadow;
    shadow.technique = o.technique;
    shadow.mapSize = o.mapSize;
    return addLight(scene, "default sun", light, shadow, center - 2.0 * size * direction, direction);
}

std::string describe(const Scene& scene, const DefaultRig& rig, const DefaultRigOptions& o) {
    char poses[96] = "";
    if (rig.posesSampled > 1) {
        std::snprintf(poses, sizeof(poses), " over %d poses of its %.3g s animation", rig.posesSampled,
                      scene.animationDuration);
    }
    char text[640];
    const DAabb& b = rig.modelBounds;
    std::snprintf(text, sizeof(text),
                  "%s: no lights; added the default rig: a %s sun %.0f degrees up, %.0f degrees right of the "
                  "view, emitter %.3g rad%s, placed from the model's bounds%s (%.3g, %.3g, %.3g) - (%.3g, %.3g, %.3g)",
                  scene.name.empty() ? "scene" : scene.name.c_str(), techniqueName(o.technique),
                  o.sunElevation / kDegree, o.sunAzimuth / kDegree, static_cast<double>(o.angularRadius),
                  rig.ground.isNull() ? "" : ", a ground under them", poses, b.min.x, b.min.y, b.min.z, b.max.x,
                  b.max.y, b.max.z);
    std::string message = text;
    if (rig.cameraAdded) message += ", and a camera framing the model and its shadow";
    return message;
}

/// The union of the model's bounds at `o.boundsSamples` times evenly over one period of the
/// animation that plays (`duration` s, looping) from `o.boundsTime`, the last period's end just
/// before it wraps to its start; one pose when nothing plays. Sampled backwards, so that the
/// world is left posed at `o.boundsTime`. `poses` gets how many were taken.
DAabb boundsOverAnimation(World& world, double duration, const DefaultRigOptions& o, int& poses) {
    const bool plays = std::isfinite(duration) && duration > 0.0;
    poses = plays ? o.boundsSamples : 1;
    const double lastOffset = plays ? std::nextafter(duration, 0.0) : 0.0;
    DAabb bounds;
    for (int k = poses - 1; k >= 0; --k) {
        const double offset = poses > 1 ? std::min(duration * k / (poses - 1), lastOffset) : 0.0;
        bounds.extend(modelBounds(world, o.boundsTime + offset));
    }
    return bounds;
}

}  // namespace

DAabb modelBounds(World& world, double t) {
    animate(world, t);
    (void)updateTransforms(world);
    DAabb bounds;
    world.view<Mesh, WorldTransform, WorldBounds>().each(
        [&](Entity, const Mesh&, const WorldTransform& wt, const WorldBounds& wb) {
            if (wt.finite) bounds.extend(wb.box);
        });
    return bounds;
}

DefaultRig addDefaultRig(Scene& scene, std::optional<Entity> camera, const DefaultRigOptions& options) {
    const DefaultRigOptions o = clamped(options);
    DefaultRig rig;
    DAabb raw = boundsOverAnimation(scene.world, scene.animationDuration, o, rig.posesSampled);
    if (raw.empty()) raw = DAabb{glm::dvec3(-1.0), glm::dvec3(1.0)};
    const double size = std::max({raw.extent().x, raw.extent().y, raw.extent().z, 1e-6});
    const double margin = o.boundsMargin * glm::length(raw.extent());
    rig.modelBounds = DAabb{raw.min - glm::dvec3(margin), raw.max + glm::dvec3(margin)};
    rig.groundHeight = raw.min.y - kGroundGap * size;

    if (!camera && !scene.cameras.empty()) camera = scene.cameras.front();
    const glm::dvec3 offset = defaultCameraOffset();
    const glm::dvec3 forward =
        camera ? horizontalForward(scene.world, *camera) : glm::normalize(glm::dvec3(-offset.x, 0.0, -offset.z));
    rig.sunDirection = sunDirection(forward, o);
    // The ground holds the shadow of the bounds with their margin; the camera frames the pose.
    const std::vector<glm::dvec3> reached = modelAndShadowPoints(rig.modelBounds, rig.sunDirection, rig.groundHeight);
    const glm::dvec3 center = raw.center();
    double reach = 0.0;
    for (const glm::dvec3& p : reached) reach = std::max({reach, std::abs(p.x - center.x), std::abs(p.z - center.z)});
    const double half = std::max(kGroundHalfMin * size, reach + kGroundBorder * size);
    if (o.ground) {
        rig.ground = addGround(scene, center, rig.groundHeight, half);
        rig.groundHalfSize = half;
    }
    rig.sun = addSun(scene, center, size, rig.sunDirection, o);
    rig.cameraAdded = !camera;
    if (camera) {
        rig.camera = *camera;
    } else {
        const glm::dvec3 g(center.x, rig.groundHeight, center.z);
        const std::array<glm::dvec3, 4> groundCorners{
            g + glm::dvec3(-half, 0.0, -half), g + glm::dvec3(half, 0.0, -half), g + glm::dvec3(-half, 0.0, half),
            g + glm::dvec3(half, 0.0, half)};
        rig.camera = addFramingCamera(scene, modelAndShadowPoints(raw, rig.sunDirection, rig.groundHeight),
                                      -glm::normalize(offset), groundCorners, o.imageAspect);
    }
    (void)updateTransforms(scene.world);  // the rig's entities posed with the model
    scene.warnings.push_back(
        {WarningCode::DefaultRigAdded, scene.name.empty() ? "scene" : scene.name, describe(scene, rig, o)});
    return rig;
}

}  // namespace shadow
