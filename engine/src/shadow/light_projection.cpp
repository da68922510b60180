#include "shadow/light_projection.h"

#include "shadow/map_memory.h"

#include <shadow/scene.h>
#include <shadow/shared_constants.h>

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <limits>
#include <optional>

namespace shadow {
namespace {

/// The step `quantizeUp` and `quantizeDown` round `x` > 0 to: `unit` times a power of two near
/// x / (16 unit). `unit` is a length the scene defines and keeps (the camera's far plane), so that
/// the same scene at another scale rounds to the same steps of its own size.
double quantizationStep(double x, double unit) { return unit * std::exp2(std::floor(std::log2(x / unit)) - 4.0); }

/// Rounds `x` > 0 up to a multiple of `quantizationStep`, so that values differing by rounding
/// noise (a camera that only rotated) give the same result.
double quantizeUp(double x, double unit) {
    if (!(x > 0.0)) return 1e-6 * unit;
    const double step = quantizationStep(x, unit);
    return std::ceil(x / step) * step;
}

/// Rounds `x` > 0 down to a multiple of the same step as `quantizeUp`.
double quantizeDown(double x, double unit) {
    if (!(x > 0.0)) return x;
    const double step = quantizationStep(x, unit);
    return std::floor(x / step) * step;
}

/// The stored depth (lsDepth, m) of the point of `box` farthest from the light of `layer`: the
/// greatest of its corners' (axial for orthographic layers, the distance from the light for
/// perspective ones, as shadow_depth.frag.glsl stores).
double farthestDepth(const ShadowLayerPlan& layer, const DAabb& box) {
    double farthest = 0.0;
    for (int k = 0; k < 8; ++k) {
        const glm::dvec3 corner((k & 1) != 0 ? box.max.x : box.min.x, (k & 2) != 0 ? box.max.y : box.min.y,
                                (k & 4) != 0 ? box.max.z : box.min.z);
        const glm::dvec3 ls(layer.lightFromWorld * glm::dvec4(corner, 1.0));
        farthest = std::max(farthest, layer.orthographic ? -ls.z : glm::length(ls));
    }
    return farthest;
}

/// The frustum of `layer`'s matrices.
Frustum frustumOf(const ShadowLayerPlan& layer) {
    return Frustum::fromMatrix(layer.clipFromLight * layer.lightFromWorld);
}

/// A layer's matrices: while they stay, so does its frustum.
struct LayerMatrices {
    glm::dmat4 lightFromWorld{0.0};
    glm::dmat4 clipFromLight{0.0};
    friend bool operator==(const LayerMatrices&, const LayerMatrices&) = default;
};

LayerMatrices matricesOf(const ShadowLayerPlan& layer) { return {layer.lightFromWorld, layer.clipFromLight}; }

/// Brings `casters`, the casters of the last gather whose bounds `meets` accepted (in entity
/// order), up to the casters of `g`: only a changed caster can have entered or left, and one
/// did exactly when an odd number of its entries in `g.changed` meet (SceneGeometry::changed).
/// Its cost grows with the changed casters in the frustum, not with the casters. False, with
/// `casters` untouched, when more than a few changed entries meet or more than a few casters
/// entered or left: finding the list anew then costs about as much.
template <typename Meets>
bool followChangedCasters(const SceneGeometry& g, const Meets& meets, std::vector<Entity>& casters) {
    constexpr std::size_t kMostMet = 256;
    constexpr std::size_t kMostCrossed = 16;
    std::array<Entity, kMostMet> met{};
    std::size_t count = 0;
    const bool few = forEachWhile(g.changedTree, g.changed, meets, [&](const BoundedEntity& c) {
        if (count == met.size()) return false;
        met[count++] = c.entity;
        return true;
    });
    if (!few) return false;
    std::sort(met.begin(), met.begin() + static_cast<std::ptrdiff_t>(count));
    std::size_t crossed = 0;  // the casters that entered or left, packed at the front of `met`
    for (std::size_t i = 0; i < count;) {
        std::size_t j = i + 1;
        while (j < count && met[j] == met[i]) ++j;
        if ((j - i) % 2 == 1) met[crossed++] = met[i];
        i = j;
    }
    if (crossed > kMostCrossed) return false;
    for (std::size_t k = 0; k < crossed; ++k) {
        const auto at = std::lower_bound(casters.begin(), casters.end(), met[k]);
        if (at != casters.end() && *at == met[k]) {
            casters.erase(at);
        } else {
            casters.insert(at, met[k]);
        }
    }
    return true;
}

/// Sets `layer.backgrounds` to the receivers of `g` that do not cast and whose bounds meet
/// `meets`, in entity order, and returns the farthest stored depth (`farthestDepth`) of their
/// boxes when `farthest` (else 0); none when the layer has no casters (a layer without is lit).
template <typename Meets>
double backgroundsIn(const SceneGeometry& g, const Meets& meets, bool farthest, ShadowLayerPlan& layer) {
    layer.backgrounds.clear();
    if (layer.casters.empty()) return 0.0;
    layer.backgrounds.reserve(g.backgrounds.size());
    double depth = 0.0;
    for (const BoundedEntity& b : g.backgrounds) {
        if (!meets(b.bounds)) continue;
        layer.backgrounds.push_back(b.entity);
        if (farthest) depth = std::max(depth, farthestDepth(layer, b.bounds));
    }
    return depth;
}

/// Sets `layer.casters` to the casters whose bounds meet the layer's frustum, in entity order,
/// with room for every caster: one moving into the layer later costs no allocation. When
/// `followed` holds the matrices the layer had when its list was last found, over the last
/// gather's geometry, and the layer still has them, the list follows the changed casters
/// (`followChangedCasters`) instead of being found anew. With `light.backgrounds` also
/// `layer.backgrounds` (`backgroundsIn`). With `light.summedMoments` (a VSSM light) also
/// `layer.momentScale` from the farthest of them and of its backgrounds, 0 without casters
/// (ShadowLayerPlan::momentScale); other lights keep 1 and skip the corners. Call once the
/// layer's matrices and depth scale are set.
void castersIn(const SceneGeometry& g, const LayerInputs& light, const std::optional<LayerMatrices>& followed,
               ShadowLayerPlan& layer) {
    const Frustum f = frustumOf(layer);
    const auto meets = [&f](const DAabb& box) { return f.intersects(box); };
    layer.casters.reserve(g.casters.size());
    const bool same = followed.has_value() && *followed == matricesOf(layer);
    if (!light.summedMoments && same && followChangedCasters(g, meets, layer.casters)) {
        if (light.backgrounds) backgroundsIn(g, meets, false, layer);
        return;
    }
    castersMeeting(g, meets, layer.casters);
    const double farthestBackground = light.backgrounds ? backgroundsIn(g, meets, light.summedMoments, layer) : 0.0;
    if (!light.summedMoments) return;
    if (layer.casters.empty()) {
        layer.momentScale = 0.0f;  // nothing to sum: no table, every lookup lit
        return;
    }
    double farthest = farthestBackground;
    forEachCaster(g, meets,
                  [&](const BoundedEntity& c) { farthest = std::max(farthest, farthestDepth(layer, c.bounds)); });
    // The power of two putting the farthest stored depth in (1/4, 1/2]; at most 2^40 (a caster
    // 10^-12 of the range away), at least 1.
    const double stored = std::clamp(farthest / std::max(static_cast<double>(layer.depthScale), 1e-30), 1e-12, 1.0);
    layer.momentScale = static_cast<float>(std::clamp(std::exp2(std::floor(std::log2(0.5 / stored))), 1.0, 0x1p40));
}

/// `layer` at its defaults, but with the storage of its caster list (and the list itself, for
/// `castersIn` to follow). Returns the matrices it had when `follow`, else nothing.
std::optional<LayerMatrices> resetLayer(ShadowLayerPlan& layer, bool follow) {
    std::optional<LayerMatrices> had;
    if (follow) had = matricesOf(layer);
    std::vector<Entity> casters = std::move(layer.casters);
    std::vector<Entity> backgrounds = std::move(layer.backgrounds);
    layer = ShadowLayerPlan{};
    layer.casters = std::move(casters);
    layer.backgrounds = std::move(backgrounds);
    return had;
}

/// The distance of a frustum's corner over its axial depth, for the tangents `tanX` and `tanY` of
/// its half-angles: a point at axial depth d lies at most d times this from the apex.
double cornerSecant(double tanX, double tanY) { return std::sqrt(1.0 + tanX * tanX + tanY * tanY); }

/// Distance from `p` to the box (0 inside).
double distanceToBox(const glm::dvec3& p, const DAabb& box) {
    const glm::dvec3 q = glm::max(glm::max(box.min - p, p - box.max), glm::dvec3(0.0));
    return glm::length(q);
}

double farthestCorner(const glm::dvec3& p, const DAabb& box) {
    double d = 0.0;
    if (box.empty()) return d;
    for (int i = 0; i < 8; ++i) d = std::max(d, glm::distance(p, box.corner(i)));
    return d;
}

/// Camera-frustum slice [a, b] (view distance) corners in world space.
std::array<glm::dvec3, 8> sliceCorners(const CameraView& cam, double a, double b) {
    const glm::dmat4 worldFromView = glm::inverse(cam.viewFromWorld);
    const double ty = std::tan(0.5 * static_cast<double>(cam.yfov));
    const double tx = ty * static_cast<double>(cam.aspect);
    std::array<glm::dvec3, 8> out{};
    for (int i = 0; i < 8; ++i) {
        const double z = (i & 4) ? b : a;
        const glm::dvec4 v((i & 1 ? 1.0 : -1.0) * tx * z, (i & 2 ? 1.0 : -1.0) * ty * z, -z, 1.0);
        out[i] = glm::dvec3(worldFromView * v);
    }
    return out;
}

/// The camera frustum in view space (x right, y up, looking along -z; view depth d = -z), from
/// the near plane to `far`: planes (n, w), inside where dot(n, p) + w >= 0, and what testing a
/// world box against them needs.
struct ViewVolume {
    glm::dmat4 viewFromWorld{1.0};
    std::array<glm::dvec4, 6> vsPlanes{};  ///< near, far, left, right, bottom, top
    /// Per plane, |n . world axis i in view space|: a world box of half-size h reaches
    /// dot(h, planeReach[p]) either side of its centre along that plane's normal.
    std::array<glm::dvec3, 6> planeReach{};
    glm::dvec3 depthReach{0.0};             ///< the same along the view axis
    std::array<glm::dvec3, 8> wsCorners{};  ///< sliceCorners(near, far)
    double near = 0.0;
    double far = 0.0;
};

ViewVolume viewVolume(const CameraView& cam, double far) {
    ViewVolume v;
    v.viewFromWorld = cam.viewFromWorld;
    v.near = cam.znear;
    v.far = far;
    const double ty = std::tan(0.5 * static_cast<double>(cam.yfov));
    const double tx = ty * static_cast<double>(cam.aspect);
    v.vsPlanes = {glm::dvec4(0.0, 0.0, -1.0, -v.near), glm::dvec4(0.0, 0.0, 1.0, far), glm::dvec4(1.0, 0.0, -tx, 0.0),
                  glm::dvec4(-1.0, 0.0, -tx, 0.0),     glm::dvec4(0.0, 1.0, -ty, 0.0), glm::dvec4(0.0, -1.0, -ty, 0.0)};
    const glm::dmat3 vsAxes(cam.viewFromWorld);  // column i: world axis i in view space
    for (std::size_t p = 0; p < v.vsPlanes.size(); ++p) {
        for (int i = 0; i < 3; ++i) v.planeReach[p][i] = std::abs(glm::dot(glm::dvec3(v.vsPlanes[p]), vsAxes[i]));
    }
    for (int i = 0; i < 3; ++i) v.depthReach[i] = std::abs(vsAxes[i].z);
    v.wsCorners = sliceCorners(cam, v.near, far);
    return v;
}

/// A convex polygon being clipped: a quad gains at most one vertex per plane, so six planes
/// leave at most ten.
struct ClipPolygon {
    std::array<glm::dvec3, 12> vertices{};
    int count = 0;
};

/// The part of `in` inside `plane` (Sutherland-Hodgman).
ClipPolygon clipAgainst(const ClipPolygon& in, const glm::dvec4& plane) {
    ClipPolygon out;
    const int capacity = static_cast<int>(out.vertices.size());
    for (int i = 0; i < in.count; ++i) {
        const glm::dvec3& a = in.vertices[static_cast<std::size_t>(i)];
        const glm::dvec3& b = in.vertices[static_cast<std::size_t>((i + 1) % in.count)];
        const double sa = glm::dot(glm::dvec3(plane), a) + plane.w;
        const double sb = glm::dot(glm::dvec3(plane), b) + plane.w;
        if (sa >= 0.0 && out.count < capacity) out.vertices[static_cast<std::size_t>(out.count++)] = a;
        if ((sa >= 0.0) != (sb >= 0.0) && out.count < capacity) {
            out.vertices[static_cast<std::size_t>(out.count++)] = a + (b - a) * (sa / (sa - sb));
        }
    }
    return out;
}

/// The view-depth interval of a box that crosses the planes of `straddled` (a bit per plane):
/// every vertex of box ∩ frustum is a vertex of a box face clipped to the frustum, or a corner
/// of the frustum inside the box (the camera inside a receiver's box), and a depth's extremes
/// over a convex polytope lie at its vertices.
std::optional<DepthInterval> clippedDepth(const ViewVolume& v, const DAabb& box, const glm::dvec3& vsCenter,
                                          const glm::dvec3& half, unsigned straddled) {
    const glm::dmat3 vsAxes(v.viewFromWorld);
    std::array<glm::dvec3, 8> corners{};
    for (int i = 0; i < 8; ++i) {
        corners[static_cast<std::size_t>(i)] = vsCenter + vsAxes[0] * ((i & 1) != 0 ? half.x : -half.x) +
                                               vsAxes[1] * ((i & 2) != 0 ? half.y : -half.y) +
                                               vsAxes[2] * ((i & 4) != 0 ? half.z : -half.z);
    }
    // Faces -x, +x, -y, +y, -z, +z by corner index, each in cyclic order.
    static constexpr std::array<std::array<int, 4>, 6> kFaces{
        {{0, 2, 6, 4}, {1, 3, 7, 5}, {0, 1, 5, 4}, {2, 3, 7, 6}, {0, 1, 3, 2}, {4, 5, 7, 6}}};
    DepthInterval range{std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};
    for (const std::array<int, 4>& face : kFaces) {
        ClipPolygon polygon;
        for (int k : face)
            polygon.vertices[static_cast<std::size_t>(polygon.count++)] = corners[static_cast<std::size_t>(k)];
        for (std::size_t p = 0; p < v.vsPlanes.size() && polygon.count > 0; ++p) {
            if ((straddled & (1u << p)) != 0) polygon = clipAgainst(polygon, v.vsPlanes[p]);
        }
        for (int i = 0; i < polygon.count; ++i) {
            const double depth = -polygon.vertices[static_cast<std::size_t>(i)].z;
            range.nearest = std::min(range.nearest, depth);
            range.farthest = std::max(range.farthest, depth);
        }
    }
    for (std::size_t c = 0; c < v.wsCorners.size(); ++c) {
        const glm::dvec3& p = v.wsCorners[c];
        if (glm::all(glm::greaterThanEqual(p, box.min)) && glm::all(glm::lessThanEqual(p, box.max))) {
            const double depth = (c & 4) != 0 ? v.far : v.near;
            range.nearest = std::min(range.nearest, depth);
            range.farthest = std::max(range.farthest, depth);
        }
    }
    if (!(range.nearest <= range.farthest)) return std::nullopt;
    return range;
}

/// The view-depth interval of the part of `box` inside the volume, if any. Most boxes are wholly
/// outside one plane or wholly inside all six (exact tests for a box against a plane, from its
/// centre and its reach along the normal); only the rest are clipped.
std::optional<DepthInterval> depthInside(const ViewVolume& v, const DAabb& box) {
    const glm::dvec3 half = 0.5 * box.extent();
    const glm::dvec3 vsCenter(v.viewFromWorld * glm::dvec4(box.center(), 1.0));
    unsigned straddled = 0;
    for (std::size_t p = 0; p < v.vsPlanes.size(); ++p) {
        const double side = glm::dot(glm::dvec3(v.vsPlanes[p]), vsCenter) + v.vsPlanes[p].w;
        const double reach = glm::dot(half, v.planeReach[p]);
        if (side + reach < 0.0) return std::nullopt;
        if (side - reach < 0.0) straddled |= 1u << p;
    }
    if (straddled != 0) return clippedDepth(v, box, vsCenter, half, straddled);
    const double reach = glm::dot(half, v.depthReach);
    return DepthInterval{-vsCenter.z - reach, -vsCenter.z + reach};
}

/// Widens [zBottom, zTop] to the light-space boxes of the casters overlapping the light-space
/// column [lo, hi] in x and y. The tree skips every node whose box lies beside the column or
/// within the range found so far: a caster inside it could not widen the range either (both
/// tests are monotone, and the range only grows), so the range comes out as a walk over every
/// caster gives it.
void zRangeOfColumn(const glm::dmat4& rotation, const SceneGeometry& g, const glm::dvec2& lo, const glm::dvec2& hi,
                    double& zTop, double& zBottom) {
    const auto mayWiden = [&](const DAabb& box) {
        const DAabb ls = transformBounds(rotation, box);
        const bool beside = ls.max.x < lo.x || ls.min.x > hi.x || ls.max.y < lo.y || ls.min.y > hi.y;
        return !beside && (ls.max.z > zTop || ls.min.z < zBottom);
    };
    forEachCaster(g, mayWiden, [&](const BoundedEntity& c) {
        const DAabb ls = transformBounds(rotation, c.bounds);
        zTop = std::max(zTop, ls.max.z);
        zBottom = std::min(zBottom, ls.min.z);
    });
}

/// The square a cascade covers in the light's view: centre (light-space xy) and edge (m).
struct CascadeSquare {
    glm::dvec2 lsCenter{0.0};
    double extent = 0.0;
};

/// The square of the camera slice [near, far]: the slice's bounding sphere (invariant under
/// camera rotation, so the texel size stays fixed while the camera turns: no shimmering), or
/// the receivers' bounds when they fit inside it; within reach of the camera; snapped to whole
/// texels so that a moving camera moves the map by whole texels only.
CascadeSquare fitCascadeSquare(const CameraView& cam, double near, double far, const glm::dmat4& rotation,
                               const DAabb& lsReceivers, const glm::dvec3& lsCamera, int mapSize, double lengthUnit) {
    const auto corners = sliceCorners(cam, near, far);
    glm::dvec3 center(0.0);
    for (const glm::dvec3& c : corners) center += c / 8.0;
    double radius = 0.0;
    for (const glm::dvec3& c : corners) radius = std::max(radius, glm::distance(c, center));
    const double unit = lengthUnit;
    CascadeSquare sq{glm::dvec2(rotation * glm::dvec4(center, 1.0)), 2.0 * quantizeUp(radius, unit)};
    // When every receiver fits inside the sphere's square, fit the receivers instead: tighter,
    // and just as stable since they only move when the scene does.
    const glm::dvec3 recvSize = lsReceivers.extent();
    if (!lsReceivers.empty() && std::max(recvSize.x, recvSize.y) <= sq.extent) {
        sq.extent = quantizeUp(std::max({recvSize.x, recvSize.y, 1e-6 * unit}), unit);
        sq.lsCenter = glm::dvec2(lsReceivers.center());
    }
    // Within reach of the camera (kMaxShadowReach), whatever the receivers' spread.
    sq.extent = std::min(sq.extent, 2.0 * kMaxShadowReach);
    sq.lsCenter =
        glm::clamp(sq.lsCenter, glm::dvec2(lsCamera) - kMaxShadowReach, glm::dvec2(lsCamera) + kMaxShadowReach);
    const double texel = sq.extent / mapSize;
    sq.lsCenter = glm::floor(sq.lsCenter / texel) * texel;
    return sq;
}

/// The light-space depth range [zBottom, zTop] of the column over the square [lo, hi]: what the
/// receivers and casters in it span, within reach of the camera, rounded out to steps of an
/// eighth of `unit` times its power of two (stable while things move inside it; `unit` as for
/// `quantizationStep`). `casterTop`: the top of the
/// highest caster in the column (-infinity without one).
void cascadeDepthRange(const glm::dmat4& rotation, const SceneGeometry& g, const DAabb& lsReceivers,
                       const glm::dvec3& lsCamera, const glm::dvec2& lo, const glm::dvec2& hi, double unit,
                       double& zTop, double& zBottom, double& casterTop) {
    casterTop = -std::numeric_limits<double>::infinity();
    // The bottom is the receivers' or a lower caster's: the walk need only look for the latter.
    zBottom = lsReceivers.empty() ? -1.0 : lsReceivers.min.z;
    zRangeOfColumn(rotation, g, lo, hi, casterTop, zBottom);
    zTop = std::max(lsReceivers.empty() ? 0.0 : lsReceivers.max.z, casterTop);
    zTop = std::clamp(zTop, lsCamera.z - kMaxShadowReach, lsCamera.z + kMaxShadowReach);
    zBottom = std::clamp(zBottom, lsCamera.z - kMaxShadowReach, zTop);
    const double step = unit * std::exp2(std::ceil(std::log2(std::max(zTop - zBottom, 1e-6 * unit) / (8.0 * unit))));
    zTop = (std::floor(zTop / step) + 1.0) * step;
    zBottom = (std::ceil(zBottom / step) - 1.0) * step;
}

/// The view depths a sun's cascades split, within `reach`. Where receivers are visible on
/// screen (`SceneGeometry::visible`), their range: every cascade then holds receivers the camera
/// sees, none is spent on the empty sky past the ground's far edge or on the space before the
/// nearest visible ground. Its ends are rounded outwards to steps of 1/16 of their power of two
/// (quantizeDown, quantizeUp): the range is exact to rounding noise, but a camera that moves or
/// turns a little keeps the same splits (and so the same cascade squares and reused layers);
/// they change in steps of at most 6 %, the size of a step of the squares' own quantized edge.
/// With no receiver visible (or the range unmeasured) the cascades reach from the receivers'
/// bounding box's nearest point to its farthest corner, the distances along rays instead of the
/// camera's axis: still where a shadow can first be seen once the camera turns to them.
DepthInterval cascadeSpan(const CameraView& cam, const SceneGeometry& g, double reach, double unit) {
    const double znear = cam.znear;
    if (const std::optional<DepthInterval> visible = visibleDepthRange(g.visible, reach)) {
        // visibleDepthRange keeps near <= nearest <= farthest <= reach.
        const double nearest = std::min(std::max(quantizeDown(visible->nearest, unit), znear), visible->nearest);
        return {nearest, std::min(quantizeUp(visible->farthest, unit), reach)};
    }
    // No receiver lies beyond the farthest corner of their bounds: do not spread texels there.
    const double toFarthestReceiver = farthestCorner(cam.wsPosition, g.receivers);
    const double distance = std::clamp(toFarthestReceiver, std::min(2.0 * znear, reach), reach);
    // Nor nearer than the nearest receiver: cascades start where shadows can first be seen.
    const double nearest =
        std::clamp(distanceToBox(cam.wsPosition, g.receivers), std::min(znear, 0.5 * distance), 0.5 * distance);
    return {nearest, distance};
}

void planDirectional(const LayerInputs& s, const CameraView& cam, const SceneGeometry& g, bool follow,
                     std::vector<ShadowLayerPlan>& layers) {
    const glm::dmat4 rotation = lookAlong(glm::dvec3(0.0), s.pose.wsDirection);
    const double reach =
        std::min(s.shadowDistance > 0.0f ? std::min<double>(s.shadowDistance, cam.zfar) : cam.zfar, kMaxShadowReach);
    const glm::dvec3 lsCamera(rotation * glm::dvec4(cam.wsPosition, 1.0));
    assert(s.cascades >= 1 && s.cascades <= SG_MAX_CASCADES);  // clamped by the planner
    std::array<double, SG_MAX_CASCADES + 1> splitStorage{};
    const std::span<double> splits(splitStorage.data(), static_cast<std::size_t>(s.cascades) + 1);
    const DepthInterval span = cascadeSpan(cam, g, reach, s.lengthUnit);
    cascadeSplits(span.nearest, span.farthest, s.cascadeSplitLambda, splits);
    const DAabb lsReceivers = transformBounds(rotation, g.receivers);

    layers.resize(static_cast<std::size_t>(s.cascades));
    for (int k = 0; k < s.cascades; ++k) {
        const CascadeSquare sq =
            fitCascadeSquare(cam, splits[k], splits[k + 1], rotation, lsReceivers, lsCamera, s.mapSize, s.lengthUnit);
        const glm::dvec2 lsCenter = sq.lsCenter;
        const double extent = sq.extent;
        double zTop = 0.0;
        double zBottom = 0.0;
        double casterTop = 0.0;
        cascadeDepthRange(rotation, g, lsReceivers, lsCamera, lsCenter - 0.5 * extent, lsCenter + 0.5 * extent,
                          s.lengthUnit, zTop, zBottom, casterTop);

        ShadowLayerPlan& layer = layers[static_cast<std::size_t>(k)];
        const std::optional<LayerMatrices> had = resetLayer(layer, follow);
        layer.orthographic = true;
        layer.lightFromWorld = glm::translate(glm::dmat4(1.0), -glm::dvec3(lsCenter, zTop)) * rotation;
        const double depthRange = zTop - zBottom;
        layer.clipFromLight = glm::ortho(-0.5 * extent, 0.5 * extent, -0.5 * extent, 0.5 * extent, 0.0, depthRange);
        layer.depthScale = static_cast<float>(depthRange);
        layer.depthNear = 0.0f;
        layer.splitFar = static_cast<float>(splits[k + 1]);
        // The nearest a blocker can be: the top of the highest caster in the column, below the
        // layer's top (which receivers and the rounding to steps may raise above it).
        layer.blockerNear = casterTop >= zBottom ? static_cast<float>(zTop - std::min(casterTop, zTop)) : 0.0f;
        castersIn(g, s, had, layer);
    }
}

/// Far plane of a perspective light: its range, or else the whole scene rounded up to a power
/// of two times `LayerInputs::lengthUnit`, so that an object moving at the edge of the scene does not change every layer's
/// projection (and force a redraw of layers whose casters did not move).
double perspectiveFar(const LayerInputs& light, const SceneGeometry& g) {
    if (light.range > 0.0f) return std::clamp<double>(light.range, 1e-3, kMaxShadowReach);
    const double unit = light.lengthUnit;
    const double fitted =
        unit * std::exp2(std::ceil(
                   std::log2(std::max(farthestCorner(light.pose.wsPosition, g.everything), 1e-6 * unit) / unit)));
    return std::min(fitted, kMaxShadowReach);
}

/// What every layer of a spot or point light shares: the tangent of its half-angle (the cone's,
/// or a cube face's 45 degrees, with two texels of margin on each side so that bilinear taps at
/// the edge stay inside the map), its far plane and its fixed near plane (0: fitted per layer).
struct PerspectiveReach {
    double tanHalf = 1.0;
    double far = 1.0;
    double fixedNear = 0.0;
};

PerspectiveReach perspectiveReach(const LayerInputs& light, const SceneGeometry& g) {
    const double margin = 1.0 + 4.0 / light.mapSize;
    const double tanHalf =
        light.type == LightType::Spot ? std::tan(static_cast<double>(light.outerConeAngle)) * margin : margin;
    return {tanHalf, perspectiveFar(light, g), light.nearPlane};
}

/// Whether a layer of `reach` fits its near plane to its casters.
bool fitsNear(const PerspectiveReach& reach) { return reach.fixedNear <= 0.0; }

/// The frustum a perspective layer looking through `lightFromWorld` fits its near plane in: its
/// own with the nearest near plane allowed.
Frustum widestFrustum(const glm::dmat4& lightFromWorld, const PerspectiveReach& reach) {
    const double minNear = reach.far * 1e-6;
    return Frustum::fromMatrix(glm::perspective(2.0 * std::atan(reach.tanHalf), 1.0, minNear, reach.far) *
                               lightFromWorld);
}

/// The largest power-of-two multiple of `unit` (LayerInputs::lengthUnit) not above `x` > 0: a
/// near plane that stays put while the nearest caster moves a little, so layers whose own
/// casters did not move are not redrawn.
double powerOfTwoBelow(double x, double unit) { return unit * std::exp2(std::floor(std::log2(x / unit))); }

/// One perspective layer of `light` looking along `direction`, into `layer`. Without a fixed
/// near plane it is fitted just before the nearest caster in the layer's widest frustum. Returns
/// that caster's distance from the light (the far plane without one).
double perspectiveLayer(const LayerInputs& light, const glm::dvec3& direction, const PerspectiveReach& reach,
                        const SceneGeometry& g, bool follow, ShadowLayerPlan& layer) {
    const glm::dvec3& position = light.pose.wsPosition;
    const double far = reach.far;
    const double tanHalf = reach.tanHalf;
    const double minNear = far * 1e-6;
    const std::optional<LayerMatrices> had = resetLayer(layer, follow);
    layer.orthographic = false;
    layer.lightFromWorld = lookAlong(position, direction);
    const double fov = 2.0 * std::atan(tanHalf);
    double near = std::min(reach.fixedNear, 0.5 * far);
    double nearest = far;
    const Frustum f = widestFrustum(layer.lightFromWorld, reach);
    forEachCaster(
        g, [&f](const DAabb& box) { return f.intersects(box); },
        [&](const BoundedEntity& c) { nearest = std::min(nearest, distanceToBox(position, c.bounds)); });
    if (fitsNear(reach)) {
        // The near plane clips by depth along the axis; a caster at distance d can be as shallow
        // as d times the cosine of the frustum's corner angle.
        const double cornerCos = 1.0 / cornerSecant(tanHalf, tanHalf);
        near = std::clamp(powerOfTwoBelow(std::max(0.9 * nearest * cornerCos, minNear), light.lengthUnit), minNear,
                          0.5 * far);
    }
    layer.clipFromLight = glm::perspective(fov, 1.0, near, far);
    // Stored depth is the distance from the light; the farthest point of the frustum is a
    // far-plane corner.
    layer.depthScale = static_cast<float>(far * cornerSecant(tanHalf, tanHalf));
    layer.depthNear = static_cast<float>(near);
    castersIn(g, light, had, layer);
    return nearest;
}

}  // namespace

void measureVisibleReceivers(const CameraView& camera, SceneGeometry& geometry) {
    VisibleReceivers& out = geometry.visible;
    if (out.measured) return;
    out.measured = true;
    out.boxes.clear();
    out.boxes.reserve(geometry.receiverBoxes.size());
    out.all = {1.0, 0.0};
    const ViewVolume volume = viewVolume(camera, std::min<double>(camera.zfar, kMaxShadowReach));
    DepthInterval all{std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};
    for (const DAabb& box : geometry.receiverBoxes) {
        const std::optional<DepthInterval> depth = depthInside(volume, box);
        // Not finite only for a camera whose own fields are not (the frustum's planes).
        if (!depth || !std::isfinite(depth->nearest) || !std::isfinite(depth->farthest)) continue;
        out.boxes.push_back(*depth);
        all.nearest = std::min(all.nearest, depth->nearest);
        all.farthest = std::max(all.farthest, depth->farthest);
    }
    if (!out.boxes.empty()) out.all = all;
}

std::optional<DepthInterval> visibleDepthRange(const VisibleReceivers& visible, double reach) {
    const DepthInterval& all = visible.all;
    if (!visible.measured || !(all.nearest <= all.farthest) || !(all.nearest <= reach)) return std::nullopt;
    if (all.farthest <= reach) return all;
    // The reach ends inside the receivers' range: fit up to the farthest visible within it.
    DepthInterval range{all.nearest, all.nearest};
    for (const DepthInterval& box : visible.boxes) {
        if (box.nearest <= reach) range.farthest = std::max(range.farthest, std::min(box.farthest, reach));
    }
    return range;
}

LightPose lightPose(const WorldTransform& wt) {
    LightPose pose;
    pose.wsPosition = glm::dvec3(wt.worldFromLocal[3]);
    pose.wsDirection = -worldOrientation(wt)[2];
    return pose;
}

bool lightAffectsView(const Light& light, const LightPose& pose, const Frustum& cameraFrustum) {
    if (light.type == LightType::Directional || light.range <= 0.0f) return true;
    return cameraFrustum.intersectsSphere(pose.wsPosition, light.range);
}

void cascadeSplits(double near, double far, double lambda, std::span<double> splits) {
    assert(splits.size() >= 2);
    const int count = static_cast<int>(splits.size()) - 1;
    near = std::max(near, 1e-6);
    far = std::max(far, near * (1.0 + 1e-6));
    for (int i = 0; i <= count; ++i) {
        const double f = static_cast<double>(i) / count;
        const double logSplit = near * std::pow(far / near, f);
        const double uniformSplit = near + (far - near) * f;
        splits[static_cast<std::size_t>(i)] = lambda * logSplit + (1.0 - lambda) * uniformSplit;
    }
    splits.front() = near;
    splits.back() = far;
}

LayerInputs layerInputs(const ShadowLightPlan& plan, const LightPose& pose, double lengthUnit) {
    LayerInputs in;
    in.lengthUnit = lengthUnit > 0.0 && std::isfinite(lengthUnit) ? lengthUnit : 1.0;
    in.type = plan.light.type;
    in.pose = pose;
    in.mapSize = plan.mapSize;
    in.range = plan.light.range;
    in.outerConeAngle = plan.light.outerConeAngle;
    in.nearPlane = plan.settings.nearPlane;
    in.cascades = plan.settings.cascades;
    in.cascadeSplitLambda = plan.settings.cascadeSplitLambda;
    in.shadowDistance = plan.settings.shadowDistance;
    in.summedMoments = plan.settings.technique == ShadowTechnique::Vssm;
    const std::optional<FilterChainKind> chain = filterChainOf(plan.settings.technique);
    in.backgrounds = chain.has_value() && *chain != FilterChainKind::MinMax;
    return in;
}

void planLayers(const LayerInputs& light, const CameraView& camera, const SceneGeometry& geometry, bool follow,
                std::vector<ShadowLayerPlan>& layers) {
    if (light.type == LightType::Directional) {
        planDirectional(light, camera, geometry, follow, layers);
        return;
    }
    const PerspectiveReach reach = perspectiveReach(light, geometry);
    double nearest = reach.far;  // the light's nearest caster over all its layers
    if (light.type == LightType::Spot) {
        layers.resize(1);
        nearest = perspectiveLayer(light, light.pose.wsDirection, reach, geometry, follow, layers[0]);
    } else {
        // Point: cube faces +X, -X, +Y, -Y, +Z, -Z, the order the shader's cubeFace() uses.
        static const glm::dvec3 kFaces[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
        layers.resize(6);
        for (std::size_t k = 0; k < 6; ++k)
            nearest = std::min(nearest, perspectiveLayer(light, kFaces[k], reach, geometry, follow, layers[k]));
    }
    // The nearest a blocker can be, the same in every layer (a search disk that leaves its cube
    // face continues on another): that caster, or a fixed near plane beyond it, which clips what
    // is nearer.
    const double clipped = fitsNear(reach) ? 0.0 : layers[0].depthNear;  // a fixed near plane, as used
    for (ShadowLayerPlan& layer : layers) layer.blockerNear = static_cast<float>(std::max(nearest, clipped));
}

void fitChainLevels(const LayerInputs& light, ShadowTechnique technique, FilterRadius radius, double maxFilterTexels,
                    int levels, const SceneGeometry& geometry, std::span<ShadowLayerPlan> layers) {
    // A lookup reads level log2(radius in the receiver's texels) (sg_regionMoments) and the one
    // above (trilinear), least where the texel is largest, most where it is smallest: a
    // cascade's texel is one size throughout, a perspective layer's grows with the axial
    // distance from the light, largest at the farthest receiver (axial distance at most that),
    // smallest at the nearest (axial distance at least its distance times the cosine of the
    // frustum's corner). The bounds of everything the engine knows, not only its receiving
    // meshes: a game's own casters (ShadowCasterDraw) may receive in its shader; with nothing
    // known, the layer's far plane and the light itself. Five per cent of margin for the
    // shader's float texel and the receiver's normal offset, which moves it a texel or so.
    constexpr double kTexelMargin = 1.05;
    // VSM and MSM-soft read level 0's fetches from the depth map itself (sg_chainMoments).
    const bool moments = technique == ShadowTechnique::Vsm || technique == ShadowTechnique::MsmSoft;
    const int base = moments ? 1 : 0;  // chainLevels gives a moment chain two levels at least
    for (ShadowLayerPlan& layer : layers) {
        layer.chainFirstLevel = base;
        layer.chainLastLevel = levels - 1;
    }
    if (technique != ShadowTechnique::Vsm || !(radius.metres > 0.0 || radius.texels > 0.0)) return;
    const bool known = !geometry.everything.empty();
    const double farthest =
        known ? farthestCorner(light.pose.wsPosition, geometry.everything) : std::numeric_limits<double>::infinity();
    const double nearest = known ? distanceToBox(light.pose.wsPosition, geometry.everything) : 0.0;
    for (ShadowLayerPlan& layer : layers) {
        const double perAxial = 2.0 / (layer.clipFromLight[0][0] * light.mapSize);  // texel per axial m
        const double widest =
            perAxial * (layer.orthographic ? 1.0 : std::min(farthest, static_cast<double>(layer.depthScale)));
        const double texels =
            std::min(std::max(radius.metres / (widest * kTexelMargin), radius.texels), maxFilterTexels);
        while (layer.chainFirstLevel + 1 < levels && std::exp2(layer.chainFirstLevel + 1) <= texels)
            ++layer.chainFirstLevel;
        // The frustum's corner: tangents 1 / P00 and 1 / P11 from the axis.
        const double cornerCos =
            layer.orthographic ? 1.0
                               : 1.0 / cornerSecant(1.0 / layer.clipFromLight[0][0], 1.0 / layer.clipFromLight[1][1]);
        const double narrowest = perAxial * (layer.orthographic ? 1.0 : nearest * cornerCos) / kTexelMargin;
        if (!(narrowest > 0.0)) continue;  // a receiver may stand at the light: every level
        const double most = std::max(radius.metres / narrowest, radius.texels * kTexelMargin);
        const int floorLevel = most > 1.0 ? static_cast<int>(std::floor(std::log2(most))) : 0;
        layer.chainLastLevel = std::clamp(floorLevel + 1, layer.chainFirstLevel, levels - 1);
    }
}

bool layersHold(const LayerInputs& light, bool cameraMoved, const SceneGeometry& geometry,
                std::span<const ShadowLayerPlan> layers) {
    // A moment technique's layers hold the receivers that do not cast too.
    if (light.backgrounds && geometry.backgroundsChanged) return false;
    const bool geometryChanged = !geometry.changed.empty() || geometry.receiversChanged || geometry.everythingChanged;
    // A sun's cascades follow the camera and every receiver and caster of the scene.
    if (light.type == LightType::Directional) return !cameraMoved && !geometryChanged;
    // Without a range the far plane follows the scene's bounds.
    if (!(light.range > 0.0f) && geometry.everythingChanged) return false;
    if (geometry.changed.empty()) return true;
    // The rest follows the casters its layers' frusta accept: those in the layer's own make its
    // list, its moment scale and whether it redraws; the nearest in the widest frustum fits the
    // near plane (and so the matrices). While no changed caster meets either, neither changes.
    for (const ShadowLayerPlan& layer : layers) {
        const Frustum own = frustumOf(layer);
        if (anyChangedMeets(geometry, [&own](const DAabb& box) { return own.intersects(box); })) return false;
    }
    const PerspectiveReach reach = perspectiveReach(light, geometry);
    if (!fitsNear(reach)) return true;
    for (const ShadowLayerPlan& layer : layers) {
        const Frustum widest = widestFrustum(layer.lightFromWorld, reach);
        if (anyChangedMeets(geometry, [&widest](const DAabb& box) { return widest.intersects(box); })) return false;
    }
    return true;
}

}  // namespace shadow
