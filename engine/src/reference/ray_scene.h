// The scene as Embree 3 sees it: every finite mesh instance flattened into world-space
// triangles, in two BVHs — one of all meshes (camera rays: what is seen) and one of the
// casters only (`Mesh::castShadows`; shadow rays: what occludes). A mesh with
// `receiveShadows = false` is in both when it casts.
//
// Precision: positions are transformed in double and stored as float *relative to the centre
// of the scene's bounds*, so a scene far from the origin keeps its precision as long as its
// own extent is moderate. Everything this class takes and returns is in world space, double.
//
// The ray epsilon follows the geometry where a ray meets it, not the scene's extent: a hit's
// offset (`SurfaceHit::epsilon`) is 2^-17 (64 float ulps) × the sum of the largest
// coordinates, relative to the centre of the scene's bounds, of the ray's origin, the hit point
// and the hit triangle's farthest vertex (at least 1e-7 m). Those three are what the float
// arithmetic rounds: the origin and the shadow ray's start as they are stored, the edge tests
// Embree evaluates from them. The error of a float hit point is a few ulps of them, so the
// offset is some 16 times that error: 0.15 mm on a ground 10 m across around the centre, seen
// from 10 m away, also when distant parts of the scene reach 10^6 m, where one epsilon for the
// whole scene (1e-5 of its diagonal, as it was) is 14 m and passes over every caster nearer
// the ground than that. A single triangle 10^6 m wide still gets metres: its float vertices
// are that coarse.
//
// What this does not do: no instancing (meshes are copied per instance), no motion blur, no
// alpha testing; a rebuild is needed when anything moves.
#pragma once

#include <shadow/ecs.h>
#include <shadow/result.h>

#include <glm/glm.hpp>
#include <memory>
#include <optional>

namespace shadow::reference {

/// The first surface a camera ray meets.
struct SurfaceHit {
    double t = 0.0;  ///< ray parameter (in units of the direction's length)
    glm::dvec3 wsPosition{0.0};
    glm::dvec3 wsNormal{0.0};     ///< unit geometric normal, on the side the ray came from
    bool receivesShadows = true;  ///< `Mesh::receiveShadows` of the mesh hit
    double epsilon = 0.0;         ///< offset of shadow rays from this hit (m); see the file comment
};

/// Embree device and the two BVHs of one frame's geometry. Thread-safe for queries.
class RayScene {
public:
    /// Builds from every entity with `Mesh` and a finite `WorldTransform`. Bad mesh data (index
    /// out of range, non-finite vertex) is an error naming the mesh; so is an Embree failure.
    [[nodiscard]] static Result<RayScene> build(World& world);

    RayScene(RayScene&&) noexcept;
    RayScene& operator=(RayScene&&) noexcept;
    ~RayScene();

    /// The nearest surface of any mesh on origin + t·direction, t in [tnear, tfar].
    [[nodiscard]] std::optional<SurfaceHit> intersect(const glm::dvec3& wsOrigin, const glm::dvec3& direction,
                                                      double tnear, double tfar) const;

    /// True when a caster lies on origin + t·direction, t in [tnear, tfar] (unit direction:
    /// t in metres).
    [[nodiscard]] bool occluded(const glm::dvec3& wsOrigin, const glm::dvec3& unitDirection, double tnear,
                                double tfar) const;

    /// The offset (m) for a point given by its world position (positions mode, where it comes
    /// from a float image): 2^-17 × its largest coordinate, relative to the scene's centre or
    /// in world space, whichever is larger (both are rounded on its way); at least 1e-7 m.
    [[nodiscard]] double epsilonAt(const glm::dvec3& wsPoint) const;
    /// Triangles in the camera BVH / the caster BVH.
    [[nodiscard]] std::size_t triangleCount() const;
    [[nodiscard]] std::size_t casterTriangleCount() const;

private:
    struct Impl;
    explicit RayScene(std::unique_ptr<Impl> impl);
    std::unique_ptr<Impl> impl_;
};

}  // namespace shadow::reference
