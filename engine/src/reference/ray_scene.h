// The scene as Embree 3 sees it: every finite mesh instance flattened into world-space
// triangles, in two BVHs — one of all meshes (camera rays: what is seen) and one of the
// casters only (`Mesh::castShadows`; shadow rays: what occludes). A mesh with
// `receiveShadows = false` is in both when it casts.
//
// Precision: positions are transformed in double and stored as float *relative to the centre
// of the scene's bounds*, so a scene far from the origin keeps its precision as long as its
// own extent is moderate. Everything this class takes and returns is in world space, double.
//
// The ray epsilon: 1e-5 × the diagonal of the scene's bounds (at least 1e-7 m). Float
// intersection points err by a few ulps of the coordinates, about 3e-7 × the extent, so the
// epsilon is some 30 times that error: 0.1 mm for a scene 10 m across.
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

    /// Offset of shadow-ray origins from the surface (m); see the file comment.
    [[nodiscard]] double epsilon() const;
    /// Triangles in the camera BVH / the caster BVH.
    [[nodiscard]] std::size_t triangleCount() const;
    [[nodiscard]] std::size_t casterTriangleCount() const;

private:
    struct Impl;
    explicit RayScene(std::unique_ptr<Impl> impl);
    std::unique_ptr<Impl> impl_;
};

}  // namespace shadow::reference
