// The transform system: world matrices parent-first, world bounds, moved flags.
#include <shadow/scene.h>

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

namespace shadow {
namespace {

enum class Visit : std::uint8_t { NotYet, InProgress, Done };

/// The unit rotation of `t`; identity for a zero or non-finite quaternion.
glm::dquat unitRotation(const Transform& t) {
    const glm::dquat q = t.rotation;
    const double len = glm::length(q);
    return (len > 0.0 && std::isfinite(len)) ? q / len : glm::dquat(1.0, 0.0, 0.0, 0.0);
}

/// `t` as a matrix, its rotation `unit` (unitRotation(t), which the caller keeps too).
glm::dmat4 localMatrix(const Transform& t, const glm::dquat& unit) {
    glm::dmat4 m = glm::mat4_cast(unit);
    m[0] *= t.scale.x;
    m[1] *= t.scale.y;
    m[2] *= t.scale.z;
    m[3] = glm::dvec4(t.translation, 1.0);
    return m;
}

struct Resolver {
    World& world;
    std::vector<Visit>& state;   // by entity index; reused across frames
    std::vector<Entity>& chain;  // scratch for resolve(); reused across frames
    TransformStats stats;

    /// Resolves `e` and its ancestors, parents first. Returns false when `e`'s matrix is not
    /// finite. A loop, not recursion: a file can hold parent chains deeper than the stack.
    bool resolve(Entity e) {
        // Walk up to the first ancestor that is resolved already (or is a root), marking the
        // entities on the way; a parent met again on the way is a cycle, with no finite answer.
        chain.clear();
        bool aboveFinite = true;
        for (Entity next = e; !next.isNull();) {
            const Visit visit = state[next.index()];
            if (visit != Visit::NotYet) {
                aboveFinite = visit == Visit::Done && world.get<WorldTransform>(next).finite;
                break;
            }
            state[next.index()] = Visit::InProgress;
            chain.push_back(next);
            const Entity parent = world.get<Transform>(next).parent;
            next = (!parent.isNull() && world.has<Transform, WorldTransform>(parent)) ? parent : Entity::null();
        }
        // Then down again, each entity after its parent.
        bool finite = aboveFinite;
        for (auto it = chain.rbegin(); it != chain.rend(); ++it) finite = update(*it, finite);
        return finite;
    }

    /// Sets the world matrix of `e`, whose parent (if any) is resolved or in a cycle;
    /// `parentFinite` is what resolving the parent answered (true for a root).
    bool update(Entity e, bool parentFinite) {
        const Transform t = world.get<Transform>(e);
        glm::dmat4 parentMatrix(1.0);
        glm::dquat parentRotation(1.0, 0.0, 0.0, 0.0);
        if (!t.parent.isNull() && world.has<Transform, WorldTransform>(t.parent)) {
            const WorldTransform& parent = world.get<WorldTransform>(t.parent);
            parentMatrix = parent.worldFromLocal;
            parentRotation = parent.rotation;
        }
        WorldTransform& wt = world.get<WorldTransform>(e);
        const glm::dquat localRotation = unitRotation(t);
        const glm::dmat4 next = parentMatrix * localMatrix(t, localRotation);
        // Renormalised at every step so that rounding does not pile up along deep chains.
        wt.rotation = glm::normalize(parentRotation * localRotation);
        const bool finite = parentFinite && isFinite(next) && insideWorld(glm::dvec3(next[3]));
        wt.movedThisFrame = wt.movedThisFrame || next != wt.worldFromLocal || finite != wt.finite;
        wt.worldFromLocal = next;
        wt.finite = finite;
        state[e.index()] = Visit::Done;
        ++stats.updated;
        if (wt.movedThisFrame) ++stats.moved;
        if (!finite) {
            ++stats.nonFinite;
            stats.skipped.push_back(e);
        }
        return finite;
    }
};

/// `box` grown by `drawn`'s weighted target displacements (`MeshData::morphBounds`): it holds
/// every morphed position of a vertex inside it.
Aabb morphedBounds(Aabb box, const MeshData& mesh, const Morph* morph) {
    if (morph == nullptr || box.empty()) return box;
    for (const MorphInfluence& m : morph->drawn) {
        if (m.target >= mesh.morphBounds.size() || mesh.morphBounds[m.target].empty()) continue;
        const glm::vec3 a = m.weight * mesh.morphBounds[m.target].min;
        const glm::vec3 b = m.weight * mesh.morphBounds[m.target].max;
        box.min += glm::min(a, b);
        box.max += glm::max(a, b);
    }
    return box;
}

/// The finite non-zero weights of `weights` among a mesh's `targets`, at most
/// `kMaxMorphInfluences` of the largest magnitude, in target order, into `out`; whether some were
/// left out.
bool chooseInfluences(const std::vector<float>& weights, std::size_t targets, std::vector<MorphInfluence>& out) {
    out.clear();
    for (std::size_t k = 0; k < std::min(weights.size(), targets); ++k) {
        if (weights[k] != 0.0f && std::isfinite(weights[k])) out.push_back({static_cast<std::uint32_t>(k), weights[k]});
    }
    if (out.size() <= kMaxMorphInfluences) return false;
    const auto larger = [](const MorphInfluence& a, const MorphInfluence& b) {
        return std::abs(a.weight) > std::abs(b.weight) ||
               (std::abs(a.weight) == std::abs(b.weight) && a.target < b.target);
    };
    std::nth_element(out.begin(), out.begin() + kMaxMorphInfluences, out.end(), larger);
    out.resize(kMaxMorphInfluences);
    std::sort(out.begin(), out.end(),
              [](const MorphInfluence& a, const MorphInfluence& b) { return a.target < b.target; });
    return true;
}

/// Picks every morphed mesh's drawn targets (`Morph::drawn`) and marks it moved when they
/// changed: its shadow layers are then redrawn like a moved mesh's, and only then.
void chooseMorphs(World& world, TransformStats& stats) {
    static thread_local std::vector<MorphInfluence> next;
    world.view<Morph, Mesh, WorldTransform>().each([&](Entity, Morph& morph, Mesh& mesh, WorldTransform& wt) {
        const std::size_t targets = mesh.data != nullptr ? mesh.data->morphTargets : 0;
        morph.truncated = chooseInfluences(morph.weights, targets, next);
        if (next == morph.drawn) return;
        morph.drawn.assign(next.begin(), next.end());
        if (!wt.movedThisFrame) {
            wt.movedThisFrame = true;
            ++stats.moved;
        }
    });
}

/// Poses every skinned mesh from its joints (see `Skin`): its matrices, its world bounds (the
/// union of each joint's posed share of the mesh, which holds every blend of them), and its moved
/// flag (set when a joint moved). A mesh with a joint missing or not finite is skipped like a
/// non-finite one.
void poseSkins(World& world, TransformStats& stats) {
    world.view<Skin, Mesh, WorldTransform, WorldBounds>().each(
        [&](Entity e, Skin& skin, Mesh& mesh, WorldTransform& wt, WorldBounds& wb) {
            skin.posed = false;
            if (!wt.finite || mesh.data == nullptr) return;
            const MeshData& data = *mesh.data;
            const Morph* morph = world.tryGet<Morph>(e);
            skin.frameFromMesh.resize(skin.joints.size());
            DAabb box;
            bool finite = !skin.joints.empty();
            bool moved = false;
            for (std::size_t j = 0; j < skin.joints.size() && finite; ++j) {
                const WorldTransform* joint = world.tryGet<WorldTransform>(skin.joints[j]);
                finite = joint != nullptr && joint->finite;
                if (!finite) break;
                moved = moved || joint->movedThisFrame;
                const glm::dmat4 worldFromMesh =
                    joint->worldFromLocal * (j < skin.inverseBind.size() ? skin.inverseBind[j] : glm::dmat4(1.0));
                if (j == 0) skin.worldFromFrame = glm::translate(glm::dmat4(1.0), glm::dvec3(joint->worldFromLocal[3]));
                glm::dmat4 frameFromMesh = worldFromMesh;
                frameFromMesh[3] -= glm::dvec4(glm::dvec3(skin.worldFromFrame[3]), 0.0);
                skin.frameFromMesh[j] = glm::mat4(frameFromMesh);
                if (j < data.jointBounds.size()) {
                    box.extend(transformBounds(worldFromMesh, morphedBounds(data.jointBounds[j], data, morph)));
                }
                finite = isFinite(worldFromMesh);
            }
            if (finite && !box.empty()) finite = insideWorld(box.min) && insideWorld(box.max);
            if (!finite) {
                wt.finite = false;
                wt.movedThisFrame = true;
                wb.box = DAabb{};
                ++stats.nonFinite;
                stats.skipped.push_back(e);
                return;
            }
            skin.posed = true;
            wb.box = box;
            if (moved && !wt.movedThisFrame) {
                wt.movedThisFrame = true;
                ++stats.moved;
            }
        });
}

}  // namespace

TransformStats updateTransforms(World& world) {
    // The moved flag speaks of this frame only.
    world.view<WorldTransform>().each([](Entity, WorldTransform& wt) { wt.movedThisFrame = false; });
    // New entities get their components first (moved = true), before any reference is held.
    std::vector<Entity> missing;
    world.view<Transform>().each([&](Entity e, Transform&) {
        if (!world.has<WorldTransform>(e)) missing.push_back(e);
    });
    for (Entity e : missing) world.emplace<WorldTransform>(e);  // movedThisFrame starts true
    missing.clear();
    world.view<Mesh>().each([&](Entity e, Mesh&) {
        if (!world.has<WorldBounds>(e)) missing.push_back(e);
    });
    for (Entity e : missing) world.emplace<WorldBounds>(e);

    static thread_local std::vector<Visit> state;
    static thread_local std::vector<Entity> chain;
    std::uint32_t maxIndex = 0;
    world.view<Transform>().each([&](Entity e, Transform&) { maxIndex = std::max(maxIndex, e.index()); });
    state.assign(static_cast<std::size_t>(maxIndex) + 1, Visit::NotYet);
    Resolver resolver{world, state, chain, {}};
    world.view<Transform, WorldTransform>().each([&](Entity e, Transform&, WorldTransform&) { resolver.resolve(e); });

    TransformStats& stats = resolver.stats;
    chooseMorphs(world, stats);
    world.view<Mesh, WorldTransform, WorldBounds>().each(
        [&](Entity e, Mesh& mesh, WorldTransform& wt, WorldBounds& wb) {
            const bool drawn = wt.finite && mesh.data != nullptr;
            wb.box = drawn ? transformBounds(wt.worldFromLocal,
                                             morphedBounds(mesh.data->bounds, *mesh.data, world.tryGet<Morph>(e)))
                           : DAabb{};
            // A mesh whose vertices reach beyond the world is skipped like a non-finite one.
            if (wt.finite && !wb.box.empty() && !(insideWorld(wb.box.min) && insideWorld(wb.box.max))) {
                wt.finite = false;
                wb.box = DAabb{};
                ++stats.nonFinite;
                stats.skipped.push_back(e);
            }
        });
    poseSkins(world, stats);
    // Last, once skinned meshes have their moved flag from their joints: a version step for each
    // update that moved the entity.
    world.view<WorldTransform>().each([](Entity, WorldTransform& wt) {
        if (wt.movedThisFrame) ++wt.version;
    });
    return stats;
}

glm::dmat3 worldOrientation(const WorldTransform& wt) {
    const glm::dmat3 m(wt.worldFromLocal);
    const double lengths = glm::length(m[0]) * glm::length(m[1]) * glm::length(m[2]);
    // Regular: every column non-zero and the three far from a plane (|det| relative to the
    // columns' lengths is the sine-like volume they span; 1e-9 keeps a 1e-20 uniform scale).
    const double det = glm::determinant(m);
    if (std::isfinite(lengths) && lengths > 0.0 && std::abs(det) > 1e-9 * lengths) {
        const glm::dvec3 z = glm::normalize(m[2]);
        const glm::dvec3 y = perpendicularPart(z, m[1]);
        return glm::dmat3(glm::cross(y, z), y, z);
    }
    return glm::mat3_cast(wt.rotation);
}

namespace {
/// The entity's `Name`, or `entity <index>` without one: how warnings name an entity.
std::string entityName(const World& world, Entity e) {
    const Name* name = world.tryGet<Name>(e);
    return name != nullptr ? name->value : "entity " + std::to_string(e.index());
}
}  // namespace

void reportSkippedTransforms(const World& world, const TransformStats& stats, std::vector<Warning>& warnings) {
    for (Entity e : stats.skipped) {
        std::string element = entityName(world, e);
        std::ostringstream msg;
        msg << element << ": world transform is not finite (NaN, Inf, or beyond " << kMaxWorldCoordinate
            << " m); skipped by every pass";
        warnings.push_back({WarningCode::NonFiniteTransform, std::move(element), msg.str()});
    }
}

void reportTruncatedMorphs(World& world, std::vector<Warning>& warnings) {
    world.view<Morph, Mesh>().each([&](Entity e, Morph& morph, Mesh& mesh) {
        if (!morph.truncated || morph.truncationReported || mesh.data == nullptr) return;
        morph.truncationReported = true;
        const std::size_t targets = std::min(morph.weights.size(), mesh.data->morphTargets);
        const auto nonZero =
            std::count_if(morph.weights.begin(), morph.weights.begin() + static_cast<std::ptrdiff_t>(targets),
                          [](float w) { return w != 0.0f && std::isfinite(w); });
        std::string element = entityName(world, e);
        std::ostringstream msg;
        msg << element << ": mesh '" << mesh.data->name << "' has " << nonZero
            << " morph weights non-zero at once, more than the " << kMaxMorphInfluences << " a draw blends; the "
            << kMaxMorphInfluences << " of largest magnitude are drawn and the rest left out";
        warnings.push_back({WarningCode::MorphTargetsDropped, std::move(element), msg.str()});
    });
}

}  // namespace shadow
