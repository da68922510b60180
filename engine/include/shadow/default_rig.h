// The default rig: a shadowed sun and a shadow-catcher ground placed from a model's bounds, for
// a scene that brings no light of its own (most glTF assets carry no KHR_lights_punctual, and
// lit by the ambient term alone they show no shadow at all). The CLIs and the viewer add it to
// a file without lights; a game may call it for the same reason.
//
// Placement (every length a multiple of the model's size, so any scale gets the same picture):
// - the model's bounds are its meshes' world bounds (skinned and morphed meshes posed), the union
//   of its poses at `DefaultRigOptions::boundsSamples` times evenly over the animation that plays
//   (`Scene::animationDuration`, from `boundsTime`; its pose at `boundsTime` alone when nothing
//   plays), grown by `boundsMargin` of their diagonal on every side: a clip that walks the model
//   away or makes it jump keeps it over the ground and in the frame;
// - the sun shines from `sunElevation` above the horizon, its light travelling `sunAzimuth` to
//   the right of the camera's horizontal forward: shadows fall away from the camera and to its
//   right, off the model's own footprint as the camera sees it;
// - the ground is a square at the bounds' lowest point (glTF's +Y is up), centred under the
//   model, wide enough to hold the model's shadow (the bounds' corners projected along the sun)
//   and at least 4x the model's largest edge;
// - without a camera, one is added looking down 25 degrees from the front-right (the direction
//   `addDefaultCamera` uses) at the model (its bounds over the animation, without the margin) and
//   its shadow, at the nearest distance that frames both in an image of `imageAspect` (5 %
//   margin).
// The sun's shadow map covers what receives in view (the planner fits it to the ground and the
// model on screen), so it follows the bounds without a length of its own.
#pragma once

#include <shadow/scene.h>

#include <optional>

namespace shadow {

/// How `addDefaultRig` lights a scene. Angles in radians.
struct DefaultRigOptions {
    /// Add the shadow-catcher ground under the model (receives, casts nothing). Default true.
    bool ground = true;
    /// The sun's height above the horizon, [10, 90] degrees. Default 50 degrees: shadows about
    /// 0.84x as long as their casters are high.
    double sunElevation = 0.8726646259971648;
    /// Angle about +Y from the camera's horizontal forward to the horizontal direction the sun's
    /// light travels (where shadows fall), positive towards the camera's right, [-180, 180]
    /// degrees. Default 60 degrees: light from over the camera's left shoulder, so the faces the
    /// camera sees are lit and the shadow falls to the right, behind.
    double sunAzimuth = 1.0471975511965976;
    /// The sun's emitter half-angle (`Light::angularRadius`, rad), [0, 0.2]. Default 0.02, four
    /// times the real sun's, so that PCSS shows a penumbra: 4 % of a caster's height wide.
    float angularRadius = 0.02f;
    /// The sun's illuminance (lux, `Light::intensity`) and colour (linear RGB).
    float intensity = 3.0f;
    glm::vec3 color{1.0f, 0.96f, 0.9f};
    /// The sun's shadow technique and map size (texels per layer edge).
    ShadowTechnique technique = ShadowTechnique::Pcss;
    int mapSize = 2048;
    /// Animation time (s) of the first pose the model's bounds are taken at; the rig leaves the
    /// world posed there. Default 0.
    double boundsTime = 0.0;
    /// Poses the bounds are the union of, evenly over one period of the animation that plays
    /// (`Scene::animationDuration` s from `boundsTime`, its end just before it loops), [1, 256].
    /// 1, or a scene whose animation lasts 0 s: the pose at `boundsTime` alone. Default 16.
    int boundsSamples = 16;
    /// Added on every side of the bounds, as a fraction of their diagonal, [0, 1]: room for the
    /// model between the sampled poses (and beyond them, with one pose), which the ground and the
    /// sun's shadow cover (the camera frames the poses themselves). Default 0.1.
    double boundsMargin = 0.1;
    /// Width / height of the images the added camera frames the model for, [0.1, 10]. Default
    /// 16:9 (the CLIs' 640x360); a narrower image cuts the sides, a wider one shows more ground.
    double imageAspect = 16.0 / 9.0;
};

/// What `addDefaultRig` added, and where.
struct DefaultRig {
    Entity sun;                    ///< the directional light, appended to `Scene::lights`
    Entity ground;                 ///< null without `DefaultRigOptions::ground`
    Entity camera;                 ///< the camera the sun was placed from
    bool cameraAdded = false;      ///< `camera` was added (the scene had none and none was given)
    DAabb modelBounds;             ///< the model's bounds over its animation, margin included
    int posesSampled = 1;          ///< poses `modelBounds` is the union of (`boundsSamples`, or 1)
    glm::dvec3 sunDirection{0.0};  ///< unit, the direction the sun's light travels
    double groundHeight = 0.0;     ///< the ground's y (m)
    double groundHalfSize = 0.0;   ///< half the ground's edge (m); 0 without a ground
};

/// The union of the world bounds of `world`'s meshes (skinned ones posed) at animation time `t`,
/// empty when no mesh has finite bounds. Poses the world at `t` (`animate`, `updateTransforms`).
[[nodiscard]] DAabb modelBounds(World& world, double t);

/// Adds the default rig to `scene` (see the header comment): a shadowed directional sun appended
/// to `scene.lights`, a ground unless `options.ground` is false, and, when `camera` is absent and
/// the scene has no camera, a camera framing the model and its shadow (appended to
/// `scene.cameras`). The sun is placed from `camera`, else the scene's first camera, else the
/// added one. Appends a `DefaultRigAdded` warning to `scene.warnings` saying what was added.
/// Options out of range are clamped. Poses the world at each sampled time and leaves it posed
/// at `options.boundsTime` (the CLIs' t = 0), the rig's entities included. A scene
/// without meshes is lit around a 2 m box at the origin. Never throws on bad input.
DefaultRig addDefaultRig(Scene& scene, std::optional<Entity> camera, const DefaultRigOptions& options = {});

}  // namespace shadow
