// The reference: per-pixel, per-light visibility of each light's emitter by Monte Carlo ray
// tracing with Embree — the truth the shadow-map techniques approximate.
//
// For every pixel the shading point is either the first surface on the camera ray (the same
// projection and pixel centres as the renderer: glm::perspective of the CameraView, pixel
// (0,0) top-left) or a world position read from an engine `position.exr`. For every light in
// `Scene::lights` order, N shadow rays go from the point to stratified samples of the emitter
// (see emitters.h); the visibility is the fraction that no caster blocks, and its standard
// error the binomial sqrt(v(1 − v)/N). For stratified samples the true error is smaller:
// the reported value is a conservative bound.
//
// Choices, stated once:
// - Visibility is geometric: a point outside a spot's cone, beyond a light's range or facing
//   away from the light (N·L ≤ 0) still gets the occlusion of the emitter by casters. The
//   shading that multiplies it is zero there anyway; V itself stays comparable.
// - Shadow rays start at the point offset by an epsilon along the geometric normal, to the side
//   of each ray's emitter sample, and stop epsilon short of the sample. So the surface a point
//   lies on never shadows that point; other parts of its mesh do. The epsilon follows the
//   geometry at the point, not the scene's size: 2^-17 (64 float ulps) × the sum of the largest
//   coordinates, relative to the scene's centre, of the camera, the point and the farthest
//   vertex of its triangle (at least 1e-7 m; engine/src/reference/ray_scene.h says why). So a
//   scene whose distant parts reach 10^6 m keeps the shadows of its small parts.
// - A pixel whose surface does not receive shadows (`Mesh::receiveShadows` false) has
//   visibility 1, as the engine writes it; a background pixel has visibility 1 too. Both have
//   standard error 0.
// - A zero-size emitter gets one ray: visibility exactly 0 or 1, standard error 0.
// - A point inside a point light's sphere sees it unoccluded (visibility 1).
// - A light without a `Light` or with a non-finite transform has visibility 1 everywhere.
//
// What this does not do: no transparency, no light shapes but the three above, no
// importance sampling by radiance (V is a fraction of the emitter's area / solid angle).
#pragma once

#include <shadow/image_io.h>
#include <shadow/result.h>
#include <shadow/scene.h>

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace shadow::reference {

/// How to trace. The defaults are those of the shadow_reference CLI.
struct ReferenceOptions {
    int width = 640;   ///< image width in pixels, [1, 16384]
    int height = 360;  ///< image height in pixels, [1, 16384]
    /// Shadow rays per pixel and light for an emitter with a size, [1, 1048576]. Default 256.
    int samples = 256;
    /// Worker threads, [0, 1024]; 0 = std::thread::hardware_concurrency(). Default 0.
    int threads = 0;
    /// Seed of the sample patterns; the images depend on it but not on `threads`.
    std::uint32_t seed = 1;
    /// World positions to shade instead of tracing camera rays: RGBA (xyz, coverage), the
    /// layout of an engine `position.exr`; A < 0.5 is background. Must be width x height.
    const ImageF* wsPositions = nullptr;
    /// Called after each finished row with (rows done, rows in all); calls are serialised but
    /// come from the worker threads.
    std::function<void(int, int)> progress;
};

/// What was traced for one light.
struct LightReference {
    int raysPerPixel = 0;            ///< 1 for a zero-size emitter, else `samples`
    double meanStandardError = 0.0;  ///< over shaded pixels (covered, receiving)
    double maxStandardError = 0.0;
    double meanVisibility = 1.0;  ///< over shaded pixels
    bool sizeClamped = false;     ///< radius / angularRadius was outside its range
    bool missing = false;         ///< no `Light` or a non-finite transform: V = 1
};

/// The reference images and how they were made.
struct ReferenceResult {
    ImageF wsPosition;                  ///< RGBA: world xyz, A = 1 on geometry, 0 elsewhere
    std::vector<ImageF> visibility;     ///< per `Scene::lights` entry, channel Y
    std::vector<ImageF> standardError;  ///< per light, sqrt(v(1 − v)/N), channel Y
    /// Per light, channel Y: 1 where the light's shading term is not zero — the surface side
    /// facing the camera faces the light's centre, inside a spot's outer cone and within the
    /// light's range — else 0. Where it is 0, visibility does not reach the image (V × shading
    /// = 0), so error reports weigh only the pixels where it is 1.
    std::vector<ImageF> lit;
    std::vector<LightReference> lights;
    int threads = 0;            ///< threads used
    double buildSeconds = 0.0;  ///< BVH build
    double traceSeconds = 0.0;  ///< tracing, wall clock
    double epsilonMin = 0.0;    ///< smallest shadow-ray offset of a shaded pixel (m)
    double epsilonMax = 0.0;    ///< largest shadow-ray offset of a shaded pixel (m)
    int coveredPixels = 0;      ///< pixels on geometry
    int nonReceiverPixels = 0;  ///< of those, on meshes that do not receive shadows
    /// Positions mode: covered pixels whose surface the camera ray did not find within
    /// 0.1 % of the distance (the position is shaded without a normal offset; `tnear` =
    /// epsilon instead).
    int positionsWithoutSurface = 0;
    /// Positions mode: covered pixels whose position lies beyond `kMaxWorldCoordinate` in some
    /// coordinate (`insideWorld` false: the engine draws nothing there, and a ray starting there
    /// is beyond what float ray tracing resolves), treated as background (not covered, V = 1).
    int positionsBeyondReach = 0;
};

/// A positions image (RGBA, the layout of an engine `position.exr`) as positions mode takes it:
/// four channels, and every covered pixel (A >= 0.5) finite. The error names the first pixel at
/// fault, `(x, y)` from the top left.
[[nodiscard]] Status checkPositions(const ImageF& positions);

/// Binomial standard error of the fraction `v` of `rays` independent rays: sqrt(v(1 − v)/rays).
/// Tests judging an estimate against an exact fraction p should also take it at p: the
/// estimate's own is 0 when every ray agrees, though p may lie just inside (0, 1).
[[nodiscard]] double binomialStandardError(double v, int rays);

/// A camera ray through image point (`px`, `py`) in pixels from the top-left corner (pixel
/// centres at +0.5). Direction not normalised: t is the view-space depth, so [znear, zfar] is
/// exactly the range the rasteriser keeps.
struct CameraRay {
    glm::dvec3 wsOrigin{0.0};
    glm::dvec3 direction{0.0, 0.0, -1.0};
    double tnear = 0.0;
    double tfar = 0.0;
};
[[nodiscard]] CameraRay cameraRay(const CameraView& camera, int width, int height, double px, double py);

/// Traces the reference for the world as it stands (animate and updateTransforms first). The
/// scene is read, not changed (`World` only has mutable views). Bad options or positions are
/// errors naming the element.
[[nodiscard]] Result<ReferenceResult> traceVisibility(Scene& scene, const CameraView& camera,
                                                      const ReferenceOptions& options);

}  // namespace shadow::reference
