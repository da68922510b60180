// ShadowPlanner: the CPU "decide" phase of the shadow system (see shadow_planner.h).
#include <shadow/distance_field.h>
#include <shadow/shadow_planner.h>
#include <shadow/shared_constants.h>

#include "core/camera.h"
#include "core/screen_bounds.h"
#include "shadow/auto_planning.h"
#include "shadow/frustum.h"
#include "shadow/emitter_radius.h"
#include "shadow/light_projection.h"
#include "shadow/map_memory.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <sstream>
#include <string_view>

namespace shadow {
namespace {

/// Clamps `value` to [lo, hi] (NaN and infinities: to `lo`), one warning when it changed.
template <typename T>
void clampField(T& value, T lo, T hi, std::string_view who, const char* field, std::vector<Warning>& warnings) {
    T clamped = value;
    if constexpr (std::is_floating_point_v<T>) {
        if (!std::isfinite(value)) clamped = lo;
    }
    clamped = std::clamp(clamped, lo, hi);
    if (clamped != value) {
        std::ostringstream msg;
        msg << who << ": " << field << " " << value << " clamped to " << clamped;
        warnings.push_back({WarningCode::SettingClamped, std::string(who), msg.str()});
        value = clamped;
    }
}

/// `clampField` for a length setting that may be `kAutomatic`, which stays as it is.
void clampLength(float& value, float lo, float hi, std::string_view who, const char* field,
                 std::vector<Warning>& warnings) {
    if (!isAutomatic(value)) clampField(value, lo, hi, who, field, warnings);
}

const char* lightName(const World& world, Entity e) {
    const Name* n = world.tryGet<Name>(e);
    return n != nullptr ? n->value.c_str() : "light";
}

/// Scene light `index` as far as the scene says, into `plan`: name, pose and unclamped `Light`;
/// no shadow yet (mapSize 0). `plan.layers` is left for `planLayers` to reuse: the caller empties
/// it if the light ends up without a map.
void describeLight(const World& world, Entity e, int index, ShadowLightPlan& plan) {
    std::string name = std::move(plan.name);
    std::vector<ShadowLayerPlan> layers = std::move(plan.layers);
    std::vector<Entity> fieldCasters = std::move(plan.fieldCasters);
    plan = ShadowLightPlan{};
    plan.name = std::move(name);
    plan.layers = std::move(layers);
    plan.fieldCasters = std::move(fieldCasters);
    plan.fieldCasters.clear();
    plan.entity = e;
    plan.sceneIndex = index;
    plan.name.assign(lightName(world, e));
    plan.settings.technique = ShadowTechnique::None;
    const Light* light = world.tryGet<Light>(e);
    const WorldTransform* wt = world.tryGet<WorldTransform>(e);
    plan.shaded = light != nullptr && wt != nullptr && wt->finite;
    if (!plan.shaded) return;
    plan.light = *light;
    const LightPose pose = lightPose(*wt);
    plan.wsPosition = pose.wsPosition;
    plan.wsDirection = pose.wsDirection;
}

/// Whether the min/max pyramid is worth building for `plan` (PCF or PCSS) this frame: when its
/// redrawn layers (with casters; a layer without is cleared, not read back) hold at most
/// `texelsPerPixel` texels per pixel the light can reach on screen, or when the image's size is
/// unknown or nothing is redrawn (a clean layer's pyramid costs nothing).
bool pyramidPays(const ShadowLightPlan& plan, const CameraView& camera, const DAabb& wsGeometry, float texelsPerPixel) {
    if (filterChainOf(plan.technique()) != FilterChainKind::MinMax) return false;
    if (!(texelsPerPixel >= 0.0f)) texelsPerPixel = 0.0f;  // NaN and negative: never when redrawn
    std::int64_t texels = 0;
    for (const ShadowLayerPlan& layer : plan.layers) {
        if (layer.dirty && !layer.casters.empty()) texels += std::int64_t{plan.mapSize} * plan.mapSize;
    }
    if (texels == 0 || camera.pixelWidth <= 0 || camera.pixelHeight <= 0) return true;
    const ScreenView view{cameraClipFromWorld(camera), camera.pixelWidth, camera.pixelHeight, wsGeometry};
    return static_cast<double>(screenBounds(plan, view).area()) * texelsPerPixel >= static_cast<double>(texels);
}

/// Smallest map edge the memory budget halves a light to before it drops its shadow.
constexpr int kMinBudgetMapSize = 256;

/// A shadowed light of the frame being planned, before its layers are.
struct Candidate {
    ShadowLightPlan* plan = nullptr;  ///< into `ShadowFrame::lights`
    bool dropped = false;             ///< by the shadow memory budget
};

/// Layers of a light's array: its cascades, one spot layer, or six cube faces.
std::int64_t layerCount(const ShadowLightPlan& plan) {
    switch (plan.light.type) {
        case LightType::Directional: return plan.settings.cascades;
        case LightType::Spot: return 1;
        case LightType::Point: return 6;
    }
    return 6;
}

/// Bytes of `plan`'s maps at its current `mapSize`: depth and the filter chain its technique
/// reads, as the shadow maps allocate them.
std::int64_t bytesOf(const ShadowLightPlan& plan) {
    return shadowMapBytes(plan.settings.technique, plan.mapSize, static_cast<int>(layerCount(plan)),
                          plan.settings.maxFilterTexels);
}

/// Candidates from least to most important: lights that cannot reach the view, then by
/// distance from the camera (directional lights at 0), farthest first, then later in the scene.
std::vector<std::size_t> budgetOrder(const std::vector<Candidate>& lights, const glm::dvec3& camera) {
    std::vector<std::size_t> order(lights.size());
    std::vector<double> distance(lights.size(), 0.0);
    for (std::size_t i = 0; i < lights.size(); ++i) {
        order[i] = i;
        const ShadowLightPlan& p = *lights[i].plan;
        if (!p.affectsView) {
            distance[i] = std::numeric_limits<double>::infinity();
        } else if (p.light.type != LightType::Directional) {
            distance[i] = glm::distance(camera, p.wsPosition);
        }
    }
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
        if (distance[a] != distance[b]) return distance[a] > distance[b];
        return lights[a].plan->sceneIndex > lights[b].plan->sceneIndex;
    });
    return order;
}

/// Fits the lights' maps into `budget` bytes by the policy of `ShadowLimits::maxShadowBytes`.
/// Allocates only over budget (a frame that also allocates its warnings).
void fitMemoryBudget(std::vector<Candidate>& lights, const glm::dvec3& camera, std::int64_t budget,
                     std::vector<Warning>& warnings) {
    std::int64_t total = 0;
    for (const Candidate& c : lights) total += bytesOf(*c.plan);
    if (total <= budget) return;
    const std::vector<std::size_t> order = budgetOrder(lights, camera);
    for (bool halved = true; total > budget && halved;) {
        halved = false;
        for (std::size_t i : order) {
            ShadowLightPlan& p = *lights[i].plan;
            if (total <= budget) break;
            if (p.mapSize <= kMinBudgetMapSize) continue;
            total -= bytesOf(p);
            p.mapSize = std::max(p.mapSize / 2, kMinBudgetMapSize);
            total += bytesOf(p);
            halved = true;
        }
    }
    for (std::size_t i : order) {
        if (total <= budget) break;
        total -= bytesOf(*lights[i].plan);
        lights[i].dropped = true;
    }
    const std::string why = " to fit the shadow memory budget (" + std::to_string(budget) + " bytes)";
    for (const Candidate& c : lights) {
        const ShadowLightPlan& p = *c.plan;
        if (c.dropped) {
            warnings.push_back({WarningCode::ShadowDropped, p.name, p.name + ": shadow dropped" + why});
        } else if (p.mapSize != p.settings.mapSize) {
            warnings.push_back({WarningCode::MapSizeReduced, p.name,
                                p.name + ": mapSize " + std::to_string(p.settings.mapSize) + " reduced to " +
                                    std::to_string(p.mapSize) + why});
        }
    }
}

/// Whether `caster` is known to be closed (watertight): a mesh by its data, a game's caster by
/// its own word.
bool knownClosed(const World& world, Entity caster) {
    if (const Mesh* mesh = world.tryGet<Mesh>(caster); mesh != nullptr && mesh->data != nullptr) {
        return mesh->data->closed;
    }
    const ShadowCasterDraw* own = world.tryGet<ShadowCasterDraw>(caster);
    return own != nullptr && own->closed;
}

/// Thinnest closed caster, in voxels of its own field, that the march reads from its field: a
/// thinner one has few or no voxels inside, and rays crossing it between samples see it as a
/// sheet of clearance near half a voxel, which lets light into its umbra.
constexpr float kMinFieldThicknessVoxels = 2.0f;

/// Why a caster of an sdf light is or is not marched through a distance field.
enum class FieldVerdict : std::uint8_t {
    Field,      ///< marched through its field
    Unfielded,  ///< a game's own draw, a skinned, morphed or cut-out mesh, or a sheared transform
    Open,       ///< not closed nor planar: its field has no inside, and rays pass between its sheets
    Thin,       ///< closed, but thinner than kMinFieldThicknessVoxels of its field
};

/// Whether `caster` can be marched through a distance field: a planar mesh (a sheet: a ground, a
/// plate) or a closed one at least kMinFieldThicknessVoxels of its field thick (its field is
/// baked from its data), placed by a rotation and
/// a scale along its own axes (a non-uniform scale gets a field of its own, baked with the scale
/// applied); a shear would break the distance bound the march steps by. A skinned or morphed
/// mesh (its field would be its base shape) and a cut-out (its field would have no holes) are not, nor an
/// open or thin one: they cast through the light's map, which poses and cuts them and holds any
/// surface, filtered as PCSS filters it.
FieldVerdict fieldVerdict(const World& world, Entity caster, int voxelBudget) {
    const Mesh* mesh = world.tryGet<Mesh>(caster);
    const WorldTransform* wt = world.tryGet<WorldTransform>(caster);
    if (mesh == nullptr || mesh->data == nullptr || mesh->data->indices.empty() || wt == nullptr || !wt->finite) {
        return FieldVerdict::Unfielded;
    }
    const Material* material = world.tryGet<Material>(caster);
    const Morph* morph = world.tryGet<Morph>(caster);
    if (world.has<Skin>(caster) || (morph != nullptr && !morph->drawn.empty()) ||
        (material != nullptr && material->cutout())) {
        return FieldVerdict::Unfielded;
    }
    std::array<glm::dvec3, 3> axes{};
    for (int c = 0; c < 3; ++c) {
        axes[static_cast<std::size_t>(c)] = glm::dvec3(wt->worldFromLocal[c]);
        if (!(glm::length(axes[static_cast<std::size_t>(c)]) > 0.0)) return FieldVerdict::Unfielded;
        axes[static_cast<std::size_t>(c)] = glm::normalize(axes[static_cast<std::size_t>(c)]);
    }
    const bool alongAxes = std::abs(glm::dot(axes[0], axes[1])) < 1e-4 && std::abs(glm::dot(axes[1], axes[2])) < 1e-4 &&
                           std::abs(glm::dot(axes[0], axes[2])) < 1e-4;
    if (!alongAxes) return FieldVerdict::Unfielded;
    const MeshData& data = *mesh->data;
    if (!data.closed) return data.planar ? FieldVerdict::Field : FieldVerdict::Open;
    DistanceFieldSettings settings;
    settings.voxelBudget = voxelBudget;
    const float voxel = distanceFieldVoxel(data.bounds, settings);
    return data.thickness >= kMinFieldThicknessVoxels * voxel ? FieldVerdict::Field : FieldVerdict::Thin;
}

/// Technique sdf: moves the casters with a field out of `plan`'s layers into `fieldCasters`
/// (once each), and warns once (`CasterWithoutField`) about those left to the map, by reason.
void takeFieldCasters(const World& world, int voxelBudget, ShadowLightPlan& plan, std::vector<Warning>& warnings) {
    std::array<int, 4> left{};  // casters left to the map, per FieldVerdict
    const auto count = [&left](FieldVerdict v) { return left[static_cast<std::size_t>(v)]; };
    const auto leftInAll = [&] {
        return count(FieldVerdict::Unfielded) + count(FieldVerdict::Open) + count(FieldVerdict::Thin);
    };
    Entity first;
    for (ShadowLayerPlan& layer : plan.layers) {
        std::erase_if(layer.casters, [&](Entity caster) {
            const FieldVerdict verdict = fieldVerdict(world, caster, voxelBudget);
            if (verdict == FieldVerdict::Field) {
                plan.fieldCasters.push_back(caster);
                return true;
            }
            if (leftInAll() == 0) first = caster;
            ++left[static_cast<std::size_t>(verdict)];
            return false;
        });
    }
    std::sort(plan.fieldCasters.begin(), plan.fieldCasters.end(),
              [](Entity a, Entity b) { return a.index() < b.index(); });
    plan.fieldCasters.erase(std::unique(plan.fieldCasters.begin(), plan.fieldCasters.end()), plan.fieldCasters.end());
    const int without = leftInAll();
    if (without == 0) return;
    const Name* name = world.tryGet<Name>(first);
    std::ostringstream msg;
    msg << plan.name << ": technique sdf: " << without << " caster draw" << (without == 1 ? "" : "s")
        << " without a distance field (";
    const char* sep = "";
    const auto part = [&](int n, const char* what) {
        if (n == 0) return;
        msg << sep << n << " " << what;
        sep = ", ";
    };
    part(count(FieldVerdict::Open), "open and not flat: a field holds no inside");
    part(count(FieldVerdict::Thin), "thinner than two voxels of their field");
    part(count(FieldVerdict::Unfielded),
         "a game's own draw, a skinned, morphed or cut-out mesh, or a sheared transform");
    msg << "; \"" << (name != nullptr ? name->value : std::string("entity ") + std::to_string(first.index()))
        << "\" first) cast through the light's shadow map, filtered as PCSS";
    warnings.push_back({WarningCode::CasterWithoutField, plan.name, msg.str()});
}

/// Technique sdf: the march lengths of `plan` left automatic (`kAutomatic`), from the median voxel
/// (m) of its field casters that are not flat: the voxel a field of `voxelBudget` voxels has over
/// the caster's mesh bounds scaled by its transform's axis scales (as the atlas bakes a
/// non-uniform scale). A flat caster's field is exact (a ground's voxel, large, says nothing of
/// the interpolation error the start offset keeps clear of). The median (the lower of two), not
/// the smallest: one small caster must not shorten every step of the light's march (a march out
/// of steps before the light reads lit). Without such casters, the flat ones' median; without
/// any, the lengths of a field one metre across. `voxels` is scratch storage.
void resolveFieldLengths(const World& world, int voxelBudget, ShadowLightPlan& plan, std::vector<double>& voxels) {
    Shadow& s = plan.settings;
    if (!isAutomatic(s.sdfStartOffset) && !isAutomatic(s.sdfMinStep)) return;
    DistanceFieldSettings settings;
    settings.voxelBudget = voxelBudget;
    double voxel = 1.0 / std::cbrt(static_cast<double>(voxelBudget));
    for (const bool flat : {false, true}) {
        voxels.clear();
        for (Entity caster : plan.fieldCasters) {
            const Mesh* mesh = world.tryGet<Mesh>(caster);
            const WorldTransform* wt = world.tryGet<WorldTransform>(caster);
            if (mesh == nullptr || mesh->data == nullptr || wt == nullptr || mesh->data->planar != flat) continue;
            const glm::vec3 scale(glm::length(glm::dvec3(wt->worldFromLocal[0])),
                                  glm::length(glm::dvec3(wt->worldFromLocal[1])),
                                  glm::length(glm::dvec3(wt->worldFromLocal[2])));
            const double v =
                distanceFieldVoxel(Aabb{mesh->data->bounds.min * scale, mesh->data->bounds.max * scale}, settings);
            if (v > 0.0) voxels.push_back(v);
        }
        if (voxels.empty()) continue;
        const auto middle = voxels.begin() + static_cast<std::ptrdiff_t>((voxels.size() - 1) / 2);
        std::nth_element(voxels.begin(), middle, voxels.end());
        voxel = *middle;
        break;
    }
    if (isAutomatic(s.sdfStartOffset)) s.sdfStartOffset = static_cast<float>(kAutoSdfStartOffsetVoxels * voxel);
    if (isAutomatic(s.sdfMinStep)) s.sdfMinStep = static_cast<float>(std::max(kAutoSdfMinStepVoxels * voxel, 1e-9));
}

/// Where each light's field casters and their clusters stand in the shader's instance buffer:
/// every light's casters in scene-light order, then every light's clusters of SG_SDF_CLUSTER.
void numberFieldCasters(std::vector<ShadowLightPlan>& lights) {
    int fields = 0;
    for (ShadowLightPlan& plan : lights) {
        plan.fieldFirst = fields;
        fields += static_cast<int>(plan.fieldCasters.size());
    }
    int clusters = fields;
    for (ShadowLightPlan& plan : lights) {
        plan.fieldClusterFirst = clusters;
        clusters += (static_cast<int>(plan.fieldCasters.size()) + SG_SDF_CLUSTER - 1) / SG_SDF_CLUSTER;
    }
}

/// One `OpenCaster` warning for a light storing a second depth whose layers hold casters not
/// known to be closed.
void warnOpenCasters(const World& world, const ShadowLightPlan& plan, std::vector<Warning>& warnings) {
    if (plan.settings.depthMode == DepthMode::Nearest) return;
    std::vector<Entity> open;  // allocated only when there is something to warn about
    for (const ShadowLayerPlan& layer : plan.layers) {
        for (Entity caster : layer.casters) {
            if (!knownClosed(world, caster) && std::find(open.begin(), open.end(), caster) == open.end()) {
                open.push_back(caster);
            }
        }
    }
    if (open.empty()) return;
    const Name* first = world.tryGet<Name>(open.front());
    std::ostringstream msg;
    msg << plan.name << ": depth mode " << depthModeName(plan.settings.depthMode) << " needs closed casters; "
        << open.size() << (open.size() == 1 ? " is" : " are") << " not (\""
        << (first != nullptr ? first->value : std::string("entity ") + std::to_string(open.front().index()))
        << "\" first): where a ray meets only one surface of them the map stores the far depth";
    warnings.push_back({WarningCode::OpenCaster, plan.name, msg.str()});
}

}  // namespace

void clampLight(Light& light, std::string_view who, std::vector<Warning>& warnings) {
    static const char* const kColor[3] = {"color.r", "color.g", "color.b"};
    for (int c = 0; c < 3; ++c) clampField(light.color[c], 0.0f, 1e3f, who, kColor[c], warnings);
    clampField(light.intensity, 0.0f, 1e12f, who, "intensity", warnings);
    clampField(light.range, 0.0f, 1e7f, who, "range", warnings);
    clampField(light.outerConeAngle, 1e-4f, 1.5707963268f, who, "outerConeAngle", warnings);
    clampField(light.innerConeAngle, 0.0f, light.outerConeAngle, who, "innerConeAngle", warnings);
    clampField(light.radius, 0.0f, 1e3f, who, "radius", warnings);
    clampField(light.angularRadius, 0.0f, 0.2f, who, "angularRadius", warnings);
}

void clampShadowSettings(Shadow& s, Light& light, const ShadowLimits& limits, const std::string& who,
                         std::vector<Warning>& warnings) {
    if (!techniqueAvailable(s.technique)) {
        // A value outside the enum, or a benchmarks' baseline in a build without them.
        const bool known = static_cast<int>(s.technique) < kShadowTechniqueCount;
        const ShadowTechnique replacement = known ? ShadowTechnique::Pcss : ShadowTechnique::Hard;
        std::ostringstream msg;
        msg << who << ": technique "
            << (known ? std::string(techniqueName(s.technique)) : std::to_string(static_cast<int>(s.technique)))
            << " is not in this build, replaced by " << techniqueName(replacement);
        warnings.push_back({WarningCode::SettingClamped, who, msg.str()});
        s.technique = replacement;
    }
    clampField(s.mapSize, 1, std::max(1, limits.maxTextureSize), who, "mapSize", warnings);
    clampLength(s.constantBias, 0.0f, 10.0f, who, "constantBias", warnings);
    clampField(s.slopeBias, 0.0f, 16.0f, who, "slopeBias", warnings);
    clampField(s.normalOffset, 0.0f, 16.0f, who, "normalOffset", warnings);
    clampLength(s.pcfRadius, 0.0f, 10.0f, who, "pcfRadius", warnings);
    clampField(s.lightBleedReduction, 0.0f, 0.95f, who, "lightBleedReduction", warnings);
    clampField(s.pcfSamples, 1, 64, who, "pcfSamples", warnings);
    clampField(s.blockerSamples, 1, 64, who, "blockerSamples", warnings);
    clampLength(s.maxFilterTexels, 1.0f, kMostFilterTexels, who, "maxFilterTexels", warnings);
    clampField(s.cascades, 1, 4, who, "cascades", warnings);
    clampField(s.cascadeSplitLambda, 0.0f, 1.0f, who, "cascadeSplitLambda", warnings);
    clampField(s.cascadeBlend, 0.0f, 0.5f, who, "cascadeBlend", warnings);
    clampField(s.shadowDistance, 0.0f, 1e7f, who, "shadowDistance", warnings);
    clampField(s.nearPlane, 0.0f, 1e7f, who, "nearPlane", warnings);
    clampField(s.sdfSteps, 4, 256, who, "sdfSteps", warnings);
    clampLength(s.sdfStartOffset, 0.0f, 1.0f, who, "sdfStartOffset", warnings);
    clampLength(s.sdfMinStep, 1e-4f, 1.0f, who, "sdfMinStep", warnings);
    clampLength(s.contactLength, 0.0f, 10.0f, who, "contactLength", warnings);
    if (static_cast<int>(s.depthMode) > static_cast<int>(DepthMode::Second)) {
        warnings.push_back({WarningCode::SettingClamped, who,
                            who + ": depthMode " + std::to_string(static_cast<int>(s.depthMode)) +
                                " is not a depth mode, replaced by nearest"});
        s.depthMode = DepthMode::Nearest;
    }
    clampLight(light, who, warnings);
    // A shadow map covers less than the half-space a spot may light.
    clampField(light.outerConeAngle, 1e-4f, kMaxSpotHalfAngle, who, "outerConeAngle", warnings);
    clampField(light.innerConeAngle, 0.0f, light.outerConeAngle, who, "innerConeAngle", warnings);
}

namespace {

/// What a scene light's layers were planned from, kept for the next frame: while none of it
/// changes (and `layersHold`), the layers stand as they are.
struct PlannedFrom {
    Entity entity;
    bool keepable = false;      ///< planned with a map, caster lists whole (not sdf), caching on
    bool affectedView = false;  ///< its layer memory holds these layers (markDirty saw them in view)
    LayerInputs inputs;
    DepthMode depthMode = DepthMode::Nearest;

    /// The same light with the same inputs to its layers and its layer memory.
    [[nodiscard]] bool samePlan(const PlannedFrom& o) const {
        return entity == o.entity && inputs == o.inputs && depthMode == o.depthMode;
    }
};

/// Every light of `lights` described into `frame.lights` and clamped once; the shadowed ones
/// become `candidates` for a map.
void collectCandidates(const World& world, const std::vector<Entity>& lights, const ShadowLimits& limits,
                       const Frustum& cameraFrustum, ShadowFrame& frame, std::vector<Candidate>& candidates) {
    candidates.clear();
    for (std::size_t i = 0; i < lights.size(); ++i) {
        ShadowLightPlan& plan = frame.lights[i];
        describeLight(world, lights[i], static_cast<int>(i), plan);
        if (!plan.shaded) continue;  // a non-finite transform is reported by the transform system
        const Shadow* shadow = world.tryGet<Shadow>(plan.entity);
        if (shadow == nullptr || shadow->technique == ShadowTechnique::None) {
            plan.settings.technique = ShadowTechnique::None;
            clampLight(plan.light, plan.name, frame.warnings);
            plan.affectsView = lightAffectsView(plan.light, {plan.wsPosition, plan.wsDirection}, cameraFrustum);
            continue;
        }
        plan.settings = *shadow;
        clampShadowSettings(plan.settings, plan.light, limits, plan.name, frame.warnings);
        plan.mapSize = plan.settings.mapSize;
        plan.affectsView = lightAffectsView(plan.light, {plan.wsPosition, plan.wsDirection}, cameraFrustum);
        candidates.push_back({&plan});
    }
}

}  // namespace

struct ShadowPlanner::Scratch {
    SceneGeometry geometry;
    std::vector<Candidate> candidates;
    std::vector<PlannedFrom> planned;      ///< this frame's, by scene light
    std::vector<PlannedFrom> lastPlanned;  ///< the last frame's
    std::optional<CameraView> lastCamera;
    std::vector<double> fieldVoxels;      ///< resolveFieldLengths' scratch
    std::vector<double> casterPenumbrae;  ///< emitterFilterRadius' scratch
};

ShadowPlanner::ShadowPlanner() : scratch_(std::make_unique<Scratch>()), auto_(std::make_unique<AutoPlanning>()) {}
ShadowPlanner::~ShadowPlanner() = default;

void ShadowPlanner::observe(const FrameStats& stats) { auto_->observe(stats); }
const AutoCostModel& ShadowPlanner::autoCosts() const { return auto_->costs(); }

const ShadowFrame& ShadowPlanner::prepare(const World& world, const CameraView& camera,
                                          const std::vector<Entity>& lights) {
    frame_.warnings.clear();
    frame_.techniquesInUse = 0;
    frame_.distanceFieldVoxels =
        std::clamp(limits_.distanceFieldVoxels, kMinDistanceFieldVoxels, kMaxDistanceFieldVoxels);
    frame_.lights.resize(lights.size());
    SceneGeometry& geometry = scratch_->geometry;
    std::vector<Candidate>& candidates = scratch_->candidates;
    gatherGeometry(world, geometry);
    std::swap(scratch_->planned, scratch_->lastPlanned);
    scratch_->planned.assign(lights.size(), PlannedFrom{});
    const bool cameraMoved = scratch_->lastCamera != camera;
    scratch_->lastCamera = camera;
    frame_.wsGeometry = geometry.everything;
    const Frustum cameraFrustum = Frustum::fromMatrix(cameraClipFromWorld(camera));

    collectCandidates(world, lights, limits_, cameraFrustum, frame_, candidates);
    auto_->choose(frame_.lights, limits_, sceneTime_, frame_.warnings);
    // Sizes first: the layers' texel snapping and margins depend on them.
    fitMemoryBudget(candidates, camera.wsPosition, limits_.maxShadowBytes, frame_.warnings);
    for (const Candidate& c : candidates) {
        ShadowLightPlan& plan = *c.plan;
        if (c.dropped) {
            plan.mapSize = 0;
            continue;
        }
        planMap(world, camera, plan, cameraMoved);
        warnOpenCasters(world, plan, frame_.warnings);
    }
    for (ShadowLightPlan& plan : frame_.lights) {
        if (plan.mapSize == 0) {
            plan.layers.clear();  // kept by describeLight in case it had a map
            plan.fieldCasters.clear();
        }
        frame_.techniquesInUse |= 1u << static_cast<unsigned>(plan.technique());
    }
    numberFieldCasters(frame_.lights);
    auto_->learn(world, camera, frame_);
    // Forget lights that are gone so their memory does not grow without bound.
    std::erase_if(memory_, [&](const auto& m) {
        return std::none_of(frame_.lights.begin(), frame_.lights.end(),
                            [&](const ShadowLightPlan& p) { return p.hasMap() && p.entity == m.first; });
    });
    return frame_;
}

void ShadowPlanner::planMap(const World& world, const CameraView& camera, ShadowLightPlan& plan, bool cameraMoved) {
    PlannedFrom& planned = scratch_->planned[static_cast<std::size_t>(plan.sceneIndex)];
    planned = {plan.entity, caching_ && plan.settings.technique != ShadowTechnique::Sdf, plan.affectsView,
               layerInputs(plan, {plan.wsPosition, plan.wsDirection}, camera.zfar), plan.settings.depthMode};
    // plan.layers still holds what this scene light was planned to last frame (describeLight).
    const auto index = static_cast<std::size_t>(plan.sceneIndex);
    const bool samePlan = index < scratch_->lastPlanned.size() && scratch_->lastPlanned[index].keepable &&
                          planned.keepable && scratch_->lastPlanned[index].samePlan(planned);
    if (!samePlan || !keepLayers(world, plan, cameraMoved)) {
        // Once a frame, and only in a frame with a sun: where receivers are visible on screen.
        if (plan.light.type == LightType::Directional) measureVisibleReceivers(camera, scratch_->geometry);
        planLayers(planned.inputs, camera, scratch_->geometry, samePlan, plan.layers);
        if (plan.settings.technique == ShadowTechnique::Sdf) {
            takeFieldCasters(world, frame_.distanceFieldVoxels, plan, frame_.warnings);
        }
        markDirty(world, plan);
    }
    if (plan.settings.technique == ShadowTechnique::Sdf)
        resolveFieldLengths(world, frame_.distanceFieldVoxels, plan, scratch_->fieldVoxels);
    plan.regionTest = pyramidPays(plan, camera, frame_.wsGeometry, limits_.pyramidTexelsPerPixel);
    const ShadowTechnique technique = plan.technique();
    const bool automaticRadius = isAutomatic(plan.settings.pcfRadius);
    // An auto light's PCF is the one-texel filter its error model was fitted on (its soft
    // choice is PCSS); PCF and VSM lights set by hand follow their emitter.
    const bool fixedWidth = technique == ShadowTechnique::Pcf || technique == ShadowTechnique::Vsm;
    plan.pcfRadiusMetres = !automaticRadius ? plan.settings.pcfRadius
                           : fixedWidth && !plan.automatic
                               ? emitterFilterRadius(planned.inputs, emitterSize(plan.light), scratch_->geometry,
                                                     plan.layers, scratch_->casterPenumbrae)
                               : 0.0;
    const bool momentRegions = technique == ShadowTechnique::MsmSoft || technique == ShadowTechnique::Vssm;
    const float margin = momentRegions ? kAutoMomentFilterTexelsMargin : kAutoFilterTexelsMargin;
    plan.maxFilterTexels =
        isAutomatic(plan.settings.maxFilterTexels)
            ? std::clamp(margin * static_cast<float>(widestPenumbraTexels(planned.inputs, emitterSize(plan.light),
                                                                          scratch_->geometry, plan.layers)),
                         kAutoLeastFilterTexels, kMostFilterTexels)
            : plan.settings.maxFilterTexels;
    fitChainLevels(planned.inputs, technique, {plan.pcfRadiusMetres, automaticRadius ? kAutoPcfRadiusTexels : 0.0},
                   plan.maxFilterTexels, chainLevels(technique, plan.mapSize, plan.settings.maxFilterTexels),
                   scratch_->geometry, plan.layers);
}

bool ShadowPlanner::keepLayers(const World& world, ShadowLightPlan& plan, bool cameraMoved) {
    const auto index = static_cast<std::size_t>(plan.sceneIndex);
    const PlannedFrom& last = scratch_->lastPlanned[index];
    const PlannedFrom& now = scratch_->planned[index];
    if (!layersHold(now.inputs, cameraMoved, scratch_->geometry, plan.layers)) return false;
    if (last.affectedView && plan.affectsView) {
        // The layer memory holds these very layers, and none of their casters moved (layersHold):
        // what markDirty would find, without walking the casters.
        for (ShadowLayerPlan& layer : plan.layers) layer.dirty = false;
    } else {
        markDirty(world, plan);
    }
    return true;
}

namespace {

/// Keeps `drawn` (a layer's casters or backgrounds) in `kept` and each one's transform version
/// in `versions`, with the layer's room for every one (planLayers): one moving in later costs
/// no allocation here either.
void rememberDrawn(const World& world, const std::vector<Entity>& drawn, std::vector<Entity>& kept,
                   std::vector<std::uint64_t>& versions) {
    kept.reserve(drawn.capacity());
    kept = drawn;
    versions.reserve(drawn.capacity());
    versions.clear();
    for (Entity e : drawn) {
        const WorldTransform* wt = world.tryGet<WorldTransform>(e);
        versions.push_back(wt != nullptr ? wt->version : 0);
    }
}

}  // namespace

void ShadowPlanner::markDirty(const World& world, ShadowLightPlan& plan) {
    auto it = std::find_if(memory_.begin(), memory_.end(), [&](const auto& m) { return m.first == plan.entity; });
    if (it == memory_.end()) {
        memory_.emplace_back(plan.entity, LightMemory{});
        it = std::prev(memory_.end());
    }
    LightMemory& mem = it->second;
    const bool reallocated = mem.mapSize != plan.mapSize || mem.layers.size() != plan.layers.size() ||
                             mem.depthMode != plan.settings.depthMode;
    if (!plan.affectsView) {
        // Nothing the camera sees is lit by it: skip the layers. Casters may move meanwhile,
        // so forget what was drawn; the light is redrawn whole when it matters again.
        for (ShadowLayerPlan& layer : plan.layers) layer.dirty = false;
        mem = LightMemory{};
        return;
    }
    if (reallocated) {
        mem.mapSize = plan.mapSize;
        mem.depthMode = plan.settings.depthMode;
        mem.layers.assign(plan.layers.size(), LayerMemory{});
    }
    for (std::size_t k = 0; k < plan.layers.size(); ++k) {
        ShadowLayerPlan& layer = plan.layers[k];
        LayerMemory& last = mem.layers[k];
        bool dirty = !caching_ || reallocated || last.lightFromWorld != layer.lightFromWorld ||
                     last.clipFromLight != layer.clipFromLight || last.casters != layer.casters ||
                     last.backgrounds != layer.backgrounds;
        for (std::size_t c = 0; !dirty && c < layer.casters.size(); ++c) {
            const WorldTransform* wt = world.tryGet<WorldTransform>(layer.casters[c]);
            const ShadowCasterDraw* own = world.tryGet<ShadowCasterDraw>(layer.casters[c]);
            dirty = wt == nullptr || wt->version != last.versions[c] || (own != nullptr && own->changedThisFrame);
        }
        for (std::size_t c = 0; !dirty && c < layer.backgrounds.size(); ++c) {
            const WorldTransform* wt = world.tryGet<WorldTransform>(layer.backgrounds[c]);
            dirty = wt == nullptr || wt->version != last.backgroundVersions[c];
        }
        layer.dirty = dirty;
        if (dirty) {
            last.lightFromWorld = layer.lightFromWorld;
            last.clipFromLight = layer.clipFromLight;
            rememberDrawn(world, layer.casters, last.casters, last.versions);
            rememberDrawn(world, layer.backgrounds, last.backgrounds, last.backgroundVersions);
        }
    }
}

}  // namespace shadow
