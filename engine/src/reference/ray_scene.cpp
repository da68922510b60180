#include "ray_scene.h"

#include <embree3/rtcore.h>
#include <shadow/components.h>
#include <shadow/math.h>

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

namespace shadow::reference {
namespace {

/// 64 float ulps (2^-17) of the magnitudes a ray's arithmetic rounds; see ray_scene.h.
constexpr double kRelativeEpsilon = 1.0 / 131072.0;
constexpr double kMinEpsilon = 1e-7;  // m

double largestCoordinate(const glm::dvec3& v) { return std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)}); }

/// A cut-out material's alpha test (`Material::cutout`), the rule of shaders/alpha_test.glsl.
struct AlphaTest {
    std::shared_ptr<const Texture> texture;  ///< null: the base alpha alone
    float alpha = 1.0f;
    float cutoff = 0.5f;
};

/// One mesh instance in world space, its triangles in the buffers Embree shares.
struct FlatMesh {
    std::vector<float> vertices;  ///< xyz per vertex relative to the scene origin, plus padding
    std::vector<std::uint32_t> indices;
    bool casts = true;
    bool receives = true;
    std::optional<AlphaTest> alphaTest;    ///< a cut-out's: hits in its holes are ignored
    std::shared_ptr<const MeshData> data;  ///< its texture coordinates, for the alpha test
};

/// A mesh instance picked for the BVHs, before flattening.
struct Instance {
    std::string name;
    glm::dmat4 worldFromLocal{1.0};
    std::shared_ptr<const MeshData> data;
    bool casts = true;
    bool receives = true;
    const Skin* skin = nullptr;    ///< a posed skin: its vertices go through it (the world outlives the build)
    const Morph* morph = nullptr;  ///< morph targets drawn: applied before the skin (the world outlives the build)
    std::optional<AlphaTest> alphaTest;
};

/// Texel coordinate `i` of an edge of `size` texels, wrapped by `wrap`.
int wrapTexel(int i, int size, Texture::Wrap wrap) {
    switch (wrap) {
        case Texture::Wrap::ClampToEdge: return std::clamp(i, 0, size - 1);
        case Texture::Wrap::MirroredRepeat: {
            const int period = 2 * size;
            const int m = ((i % period) + period) % period;
            return m < size ? m : period - 1 - m;
        }
        default: return ((i % size) + size) % size;
    }
}

/// The texture's alpha at `uv`, bilinear over the full-resolution image (the GPU's level 0).
float sampleAlpha(const Texture& t, const glm::vec2& uv) {
    const float x = uv.x * static_cast<float>(t.width) - 0.5f;
    const float y = uv.y * static_cast<float>(t.height) - 0.5f;
    if (!std::isfinite(x) || !std::isfinite(y)) return 1.0f;
    const float fx = std::floor(x);
    const float fy = std::floor(y);
    // Far outside [0, 1] float loses the fraction: the texel at the wrapped integer stands alone.
    const double big = 1 << 24;
    const int x0 = static_cast<int>(std::fmod(static_cast<double>(fx), big));
    const int y0 = static_cast<int>(std::fmod(static_cast<double>(fy), big));
    const float ax = x - fx;
    const float ay = y - fy;
    const auto texel = [&](int i, int j) {
        const int u = wrapTexel(i, t.width, t.wrapS);
        const int v = wrapTexel(j, t.height, t.wrapT);
        return static_cast<float>(t.rgba[(static_cast<std::size_t>(v) * static_cast<std::size_t>(t.width) +
                                          static_cast<std::size_t>(u)) *
                                             4U +
                                         3U]) /
               255.0f;
    };
    const float top = texel(x0, y0) * (1.0f - ax) + texel(x0 + 1, y0) * ax;
    const float bottom = texel(x0, y0 + 1) * (1.0f - ax) + texel(x0 + 1, y0 + 1) * ax;
    return top * (1.0f - ay) + bottom * ay;
}

/// Whether the hit at barycentrics (u, v) of triangle `primitive` of `mesh` falls in a hole.
bool inHole(const FlatMesh& mesh, unsigned primitive, float u, float v) {
    const AlphaTest& test = *mesh.alphaTest;
    float alpha = test.alpha;
    const std::vector<glm::vec2>& uv = mesh.data->texcoords;
    if (test.texture != nullptr) {
        glm::vec2 at(0.0f);
        if (uv.size() == mesh.data->positions.size()) {
            const std::uint32_t* tri = &mesh.indices[std::size_t{3} * primitive];
            at = (1.0f - u - v) * uv[tri[0]] + u * uv[tri[1]] + v * uv[tri[2]];
        }
        alpha *= sampleAlpha(*test.texture, at);
    }
    return alpha < test.cutoff;
}

/// Embree's filter for cut-out geometry: a hit in a hole is no hit.
void alphaFilter(const RTCFilterFunctionNArguments* args) {
    const auto* mesh = static_cast<const FlatMesh*>(args->geometryUserPtr);
    for (unsigned i = 0; i < args->N; ++i) {
        if (args->valid[i] == 0) continue;
        const float u = RTCHitN_u(args->hit, args->N, i);
        const float v = RTCHitN_v(args->hit, args->N, i);
        if (inHole(*mesh, RTCHitN_primID(args->hit, args->N, i), u, v)) args->valid[i] = 0;
    }
}

std::string meshName(const World& world, Entity e, const MeshData& data) {
    if (const Name* n = world.tryGet<Name>(e); n != nullptr && !n->value.empty()) return n->value;
    return data.name.empty() ? "entity " + std::to_string(e.index()) : data.name;
}

/// Mesh data Embree could read out of bounds or that would poison the BVH is bad input.
Status validate(const Instance& instance) {
    const MeshData& d = *instance.data;
    if (d.indices.size() % 3 != 0) {
        return Error{ErrorCode::InvalidValue, "mesh '" + instance.name + "': index count " +
                                                  std::to_string(d.indices.size()) + " is not a multiple of 3"};
    }
    for (const std::uint32_t i : d.indices) {
        if (i >= d.positions.size()) {
            return Error{ErrorCode::InvalidValue, "mesh '" + instance.name + "': index " + std::to_string(i) +
                                                      " out of range (" + std::to_string(d.positions.size()) +
                                                      " vertices)"};
        }
    }
    for (const glm::vec3& p : d.positions) {
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
            return Error{ErrorCode::InvalidValue, "mesh '" + instance.name + "': a vertex position is not finite"};
        }
    }
    return Ok{};
}

void recordEmbreeError(void* user, RTCError code, const char* message) {
    if (code == RTC_ERROR_NONE) return;
    auto* sink = static_cast<std::pair<std::mutex, std::string>*>(user);
    const std::lock_guard<std::mutex> lock(sink->first);
    if (sink->second.empty()) sink->second = message != nullptr ? message : "unknown error";
}

/// Every mesh instance with triangles and a finite world transform, in creation order.
std::vector<Instance> gatherInstances(World& world) {
    std::vector<Instance> instances;
    world.view<Mesh, WorldTransform>().each([&](Entity e, Mesh& mesh, WorldTransform& wt) {
        if (!wt.finite || mesh.data == nullptr || mesh.data->indices.empty()) return;
        const Skin* skin = world.tryGet<Skin>(e);
        if (skin != nullptr && !skin->posed) return;
        std::optional<AlphaTest> alphaTest;
        if (const Material* m = world.tryGet<Material>(e); m != nullptr && m->cutout()) {
            alphaTest = AlphaTest{m->baseColorTexture, m->alpha, m->alphaCutoff};
        }
        const Morph* morph = world.tryGet<Morph>(e);
        instances.push_back({meshName(world, e, *mesh.data), skin != nullptr ? skin->worldFromFrame : wt.worldFromLocal,
                             mesh.data, mesh.castShadows, mesh.receiveShadows, skin,
                             morph != nullptr && !morph->drawn.empty() ? morph : nullptr, std::move(alphaTest)});
    });
    // The view walks its pool back to front; keep a stable, readable order (creation order).
    std::reverse(instances.begin(), instances.end());
    return instances;
}

/// Each instance's vertices in world space, in double, after checking its mesh data;
/// `bounds` grows to hold them all.
Result<std::vector<std::vector<glm::dvec3>>> worldPositions(const std::vector<Instance>& instances, DAabb& bounds) {
    std::vector<std::vector<glm::dvec3>> wsPositions;
    for (const Instance& instance : instances) {
        if (Status s = validate(instance); !s) return s.error();
        std::vector<glm::dvec3>& ws = wsPositions.emplace_back();
        ws.reserve(instance.data->positions.size());
        const MeshData& d = *instance.data;
        const bool skinned =
            instance.skin != nullptr && d.joints.size() == d.positions.size() && d.weights.size() == d.positions.size();
        for (std::size_t i = 0; i < d.positions.size(); ++i) {
            // Morphed, then skinned, as the vertex shader does it (shaders/mesh_vertex.glsl).
            const glm::vec3 morphed =
                instance.morph != nullptr ? morphedPosition(d, *instance.morph, i) : d.positions[i];
            const glm::vec3 p = skinned ? skinnedPosition(d, *instance.skin, i, morphed) : morphed;
            ws.emplace_back(instance.worldFromLocal * glm::dvec4(glm::dvec3(p), 1.0));
            bounds.extend(ws.back());
        }
    }
    return wsPositions;
}

}  // namespace

struct RayScene::Impl {
    RTCDevice device = nullptr;
    RTCScene all = nullptr;      ///< every mesh: camera rays
    RTCScene casters = nullptr;  ///< casters only: shadow rays
    std::vector<FlatMesh> meshes;
    glm::dvec3 origin{0.0};
    std::size_t triangles = 0;
    std::size_t casterTriangles = 0;
    std::pair<std::mutex, std::string> error;

    Impl() = default;
    Impl(const Impl&) = delete;
    Impl& operator=(const Impl&) = delete;
    ~Impl() {
        if (casters != nullptr) rtcReleaseScene(casters);
        if (all != nullptr) rtcReleaseScene(all);
        if (device != nullptr) rtcReleaseDevice(device);
    }

    [[nodiscard]] glm::vec3 local(const glm::dvec3& ws) const { return glm::vec3(ws - origin); }

    /// The largest coordinate of triangle `primitive` of geometry `geometry` (scene-local).
    [[nodiscard]] double triangleMagnitude(unsigned geometry, unsigned primitive) const {
        const FlatMesh& mesh = meshes[geometry];
        double largest = 0.0;
        for (std::size_t k = 0; k < 3; ++k) {
            const std::size_t v = mesh.indices[3 * static_cast<std::size_t>(primitive) + k];
            for (std::size_t c = 0; c < 3; ++c) largest = std::max(largest, std::abs(double{mesh.vertices[3 * v + c]}));
        }
        return largest;
    }

    void attach(RTCScene scene, const FlatMesh& mesh, unsigned id) const {
        RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
        rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, mesh.vertices.data(), 0,
                                   3 * sizeof(float), (mesh.vertices.size() - 4) / 3);
        if (mesh.alphaTest) {
            rtcSetGeometryUserData(
                g, const_cast<FlatMesh*>(&mesh));  // NOLINT(cppcoreguidelines-pro-type-const-cast): Embree's void*
            rtcSetGeometryIntersectFilterFunction(g, alphaFilter);
            rtcSetGeometryOccludedFilterFunction(g, alphaFilter);
        }
        rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, mesh.indices.data(), 0,
                                   3 * sizeof(std::uint32_t), mesh.indices.size() / 3);
        rtcCommitGeometry(g);
        rtcAttachGeometryByID(scene, g, id);
        rtcReleaseGeometry(g);
    }

    /// The device, its error sink, and the two empty scenes.
    [[nodiscard]] Status createDevice() {
        device = rtcNewDevice(nullptr);
        if (device == nullptr) return Error{ErrorCode::GlUnavailable, "Embree: cannot create a device"};
        rtcSetDeviceErrorFunction(device, recordEmbreeError, &error);
        all = rtcNewScene(device);
        casters = rtcNewScene(device);
        for (RTCScene scene : {all, casters}) {
            // Robust traversal: no ray slips between two triangles sharing an edge.
            rtcSetSceneFlags(scene, RTC_SCENE_FLAG_ROBUST);
            rtcSetSceneBuildQuality(scene, RTC_BUILD_QUALITY_HIGH);
        }
        return Ok{};
    }

    /// Flattens `instance` (world-space vertices `ws`) into `meshes` and attaches it as
    /// geometry `id` to the camera BVH, and to the caster BVH when it casts. `meshes` must
    /// have room for it: Embree keeps pointers into the earlier meshes' buffers.
    void addMesh(const Instance& instance, const std::vector<glm::dvec3>& ws, unsigned id) {
        assert(meshes.size() < meshes.capacity());
        FlatMesh& mesh = meshes.emplace_back();
        mesh.casts = instance.casts;
        mesh.receives = instance.receives;
        mesh.alphaTest = instance.alphaTest;
        mesh.data = instance.data;
        // Embree reads vertices with 16-byte loads: pad the last one.
        mesh.vertices.reserve(ws.size() * 3 + 4);
        for (const glm::dvec3& p : ws) {
            const glm::vec3 v = local(p);
            mesh.vertices.insert(mesh.vertices.end(), {v.x, v.y, v.z});
        }
        mesh.vertices.insert(mesh.vertices.end(), 4, 0.0f);
        mesh.indices = instance.data->indices;
        attach(all, mesh, id);
        triangles += mesh.indices.size() / 3;
        if (mesh.casts) {
            attach(casters, mesh, id);
            casterTriangles += mesh.indices.size() / 3;
        }
    }

    [[nodiscard]] Status embreeStatus(const std::string& what) {
        const std::lock_guard<std::mutex> lock(error.first);
        if (error.second.empty()) return Ok{};
        return Error{ErrorCode::GlUnavailable, "Embree: " + what + ": " + error.second};
    }
};

RayScene::RayScene(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
RayScene::RayScene(RayScene&&) noexcept = default;
RayScene& RayScene::operator=(RayScene&&) noexcept = default;
RayScene::~RayScene() = default;

Result<RayScene> RayScene::build(World& world) {
    const std::vector<Instance> instances = gatherInstances(world);
    DAabb bounds;
    auto wsPositions = worldPositions(instances, bounds);
    if (!wsPositions) return wsPositions.error();

    auto impl = std::make_unique<Impl>();
    if (!bounds.empty()) impl->origin = bounds.center();
    if (Status s = impl->createDevice(); !s) return s.error();
    impl->meshes.reserve(instances.size());
    for (std::size_t k = 0; k < instances.size(); ++k) {
        impl->addMesh(instances[k], (*wsPositions)[k], static_cast<unsigned>(k));
    }
    rtcCommitScene(impl->all);
    rtcCommitScene(impl->casters);
    if (Status s = impl->embreeStatus("building the BVH"); !s) return s.error();
    return RayScene(std::move(impl));
}

std::optional<SurfaceHit> RayScene::intersect(const glm::dvec3& wsOrigin, const glm::dvec3& direction, double tnear,
                                              double tfar) const {
    const Impl& m = *impl_;
    const glm::vec3 o = m.local(wsOrigin);
    const glm::vec3 d(direction);
    RTCRayHit rh{};
    rh.ray.org_x = o.x;
    rh.ray.org_y = o.y;
    rh.ray.org_z = o.z;
    rh.ray.dir_x = d.x;
    rh.ray.dir_y = d.y;
    rh.ray.dir_z = d.z;
    rh.ray.tnear = static_cast<float>(tnear);
    rh.ray.tfar = static_cast<float>(tfar);
    rh.ray.mask = 0xffffffffu;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    rtcIntersect1(m.all, &context, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return std::nullopt;

    SurfaceHit hit;
    hit.t = rh.ray.tfar;
    hit.wsPosition = wsOrigin + hit.t * direction;
    const glm::dvec3 ng(rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z);
    const double length = glm::length(ng);
    hit.wsNormal = length > 0.0 ? ng / length : -glm::normalize(direction);
    if (glm::dot(hit.wsNormal, direction) > 0.0) hit.wsNormal = -hit.wsNormal;
    hit.receivesShadows = m.meshes[rh.hit.geomID].receives;
    const double magnitude = largestCoordinate(wsOrigin - m.origin) + largestCoordinate(hit.wsPosition - m.origin) +
                             m.triangleMagnitude(rh.hit.geomID, rh.hit.primID);
    hit.epsilon = std::max(kRelativeEpsilon * magnitude, kMinEpsilon);
    return hit;
}

bool RayScene::occluded(const glm::dvec3& wsOrigin, const glm::dvec3& unitDirection, double tnear, double tfar) const {
    const Impl& m = *impl_;
    const glm::vec3 o = m.local(wsOrigin);
    const glm::vec3 d(unitDirection);
    RTCRay ray{};
    ray.org_x = o.x;
    ray.org_y = o.y;
    ray.org_z = o.z;
    ray.dir_x = d.x;
    ray.dir_y = d.y;
    ray.dir_z = d.z;
    ray.tnear = static_cast<float>(tnear);
    ray.tfar = std::isinf(tfar) ? std::numeric_limits<float>::infinity() : static_cast<float>(tfar);
    ray.mask = 0xffffffffu;
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    rtcOccluded1(m.casters, &context, &ray);
    // Embree marks an occluded ray by setting tfar to -inf.
    return ray.tfar < 0.0f;
}

double RayScene::epsilonAt(const glm::dvec3& wsPoint) const {
    const double magnitude = std::max(largestCoordinate(wsPoint - impl_->origin), largestCoordinate(wsPoint));
    return std::max(kRelativeEpsilon * magnitude, kMinEpsilon);
}
std::size_t RayScene::triangleCount() const { return impl_->triangles; }
std::size_t RayScene::casterTriangleCount() const { return impl_->casterTriangles; }

}  // namespace shadow::reference
