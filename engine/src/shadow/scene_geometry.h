// The scene's shadow-relevant geometry for one frame: casters and receivers with their world
// bounds, what changed since the last frame, and the index of the casters every light's queries
// walk. Gathered once a frame by the planner, read by every light's layer fitting.
#pragma once

#include <shadow/ecs.h>
#include <shadow/math.h>

#include "shadow/box_tree.h"

#include <algorithm>
#include <cstdint>
#include <vector>

namespace shadow {

/// A range of view depth (m along the camera's axis, the depth cascades split).
struct DepthInterval {
    double nearest = 0.0;
    double farthest = 0.0;
};

/// Where the receivers are visible on screen: the view depths of their boxes clipped to the
/// camera frustum (near plane to the far plane, at most `kMaxShadowReach`). Exact for the boxes
/// (not for the surfaces inside them, nor for occlusion); what directional cascades split.
struct VisibleReceivers {
    bool measured = false;  ///< set by `measureVisibleReceivers`, cleared by `gatherGeometry`
    /// One interval per receiver box that meets the frustum, in no particular order: a light
    /// whose shadowDistance ends inside a gap between receivers fits up to the last of them.
    std::vector<DepthInterval> boxes;
    DepthInterval all{1.0, 0.0};  ///< the union's bounds; nearest > farthest when none is visible
};

/// The scene's shadow-relevant geometry for one frame, and how it differs from the last
/// `gatherGeometry`'s.
struct SceneGeometry {
    std::vector<BoundedEntity> casters;  ///< finite meshes with castShadows and the game's casters, entity order
    std::vector<DAabb> receiverBoxes;    ///< finite meshes with receiveShadows, each
    /// Finite meshes with receiveShadows but not castShadows, entity order: what a moment
    /// technique's layer holds behind its casters (ShadowLayerPlan::backgrounds).
    std::vector<BoundedEntity> backgrounds;
    DAabb receivers;           ///< union of `receiverBoxes`
    DAabb everything;          ///< union of all finite meshes and the game's casters
    VisibleReceivers visible;  ///< `measureVisibleReceivers`, for directional lights

    /// `casters` indexed, built or refitted by `gatherGeometry` when there are more than a few.
    /// Without it (a few casters, or geometry filled in by hand) queries walk the list.
    BoxTree casterTree;
    /// What can change a layer's casters or make it redraw since the last gather: the box each
    /// changed caster left and the one it took. One that appeared has only the one it took, one
    /// that disappeared only the one it left; one that moved within its bounds or whose geometry
    /// changed (`moved`) has its box twice. So a caster entered or left a fixed frustum exactly
    /// when an odd number of its entries meet it.
    std::vector<BoundedEntity> changed;
    BoxTree changedTree;           ///< `changed` indexed, when more than a few
    bool receiversChanged = true;  ///< `receiverBoxes` differ from the last gather's
    /// `backgrounds` differ from the last gather's: entities, bounds or transform versions.
    bool backgroundsChanged = true;
    bool everythingChanged = true;  ///< `everything` differs from the last gather's

    /// The last gather's lists, compared with the next (kept for their storage).
    std::vector<BoundedEntity> lastCasters;
    std::vector<DAabb> lastReceiverBoxes;
    std::vector<BoundedEntity> lastBackgrounds;
};

/// Collects casters and receivers from meshes with finite world transforms and triangles (and
/// the game's `ShadowCasterDraw`s) into `out`, reusing its storage, and compares them with what
/// it collected last time (`changed`, `receiversChanged`, `everythingChanged`): the caster
/// tree is rebuilt when casters came or went, refitted when only their bounds changed, kept
/// otherwise. `out.visible` is left unmeasured. Allocation-free once the lists have grown.
void gatherGeometry(const World& world, SceneGeometry& out);

/// Calls `visit(item)` for the items whose bounds the monotone test `meets` accepts (see
/// `BoxTree`), in no particular order, while `visit` returns true; false when it stopped.
/// Through `tree` when it indexes `items`, else over the whole list (a few items, or geometry
/// filled in by hand).
template <typename Meets, typename Visit>
bool forEachWhile(const BoxTree& tree, const std::vector<BoundedEntity>& items, const Meets& meets,
                  const Visit& visit) {
    if (tree.size() == items.size()) {
        return tree.forEachWhile(meets, [&](std::uint32_t i) { return visit(items[i]); });
    }
    for (const BoundedEntity& item : items) {
        if (meets(item.bounds) && !visit(item)) return false;
    }
    return true;
}

/// `forEachWhile` over the casters of `g`.
template <typename Meets, typename Visit>
bool forEachCasterWhile(const SceneGeometry& g, const Meets& meets, const Visit& visit) {
    return forEachWhile(g.casterTree, g.casters, meets, visit);
}

/// Whether the monotone test `meets` accepts the box of a changed caster of `g` (one it left or
/// one it took).
template <typename Meets>
[[nodiscard]] bool anyChangedMeets(const SceneGeometry& g, const Meets& meets) {
    return !forEachWhile(g.changedTree, g.changed, meets, [](const BoundedEntity&) { return false; });
}

/// `forEachCasterWhile` to the end.
template <typename Meets, typename Visit>
void forEachCaster(const SceneGeometry& g, const Meets& meets, const Visit& visit) {
    (void)forEachCasterWhile(g, meets, [&](const BoundedEntity& c) {
        visit(c);
        return true;
    });
}

/// Sets `out` to the entities of the casters of `g` that the monotone test `meets` accepts, in
/// entity order (the order of `g.casters`). Through the tree a few are found and sorted; once
/// they pass an eighth of the casters, a walk down the list, which costs less than sorting
/// them, finds them all (as it does without a tree).
template <typename Meets>
void castersMeeting(const SceneGeometry& g, const Meets& meets, std::vector<Entity>& out) {
    out.clear();
    const std::size_t few = g.casters.size() / 8;
    const bool indexed = g.casterTree.size() == g.casters.size();
    if (indexed && g.casterTree.forEachWhile(meets, [&](std::uint32_t i) {
            out.push_back(g.casters[i].entity);
            return out.size() <= few;
        })) {
        std::sort(out.begin(), out.end());
        return;
    }
    out.clear();
    for (const BoundedEntity& c : g.casters) {
        if (meets(c.bounds)) out.push_back(c.entity);
    }
}

}  // namespace shadow
