#include "shadow/scene_geometry.h"

#include <shadow/caster_draw.h>
#include <shadow/components.h>

#include <algorithm>

namespace shadow {
namespace {

/// Fewer boxes than this are walked, not indexed: the walk costs less than keeping a tree.
constexpr std::size_t kIndexedItems = 32;

bool byEntity(const BoundedEntity& a, const BoundedEntity& b) { return a.entity < b.entity; }

/// Sorts `items` by entity. A world that only ever created its meshes comes out of a view
/// exactly reversed.
void inEntityOrder(std::vector<BoundedEntity>& items) {
    if (std::is_sorted(items.rbegin(), items.rend(), byEntity)) {
        std::reverse(items.begin(), items.end());
    } else if (!std::is_sorted(items.begin(), items.end(), byEntity)) {
        std::sort(items.begin(), items.end(), byEntity);
    }
}

/// How this gather's casters differ from the last one's.
struct CasterDiff {
    bool sameEntities = true;  ///< the same casters in the same order: the tree's items stand
    bool boundsMoved = false;  ///< some caster's bounds differ: the tree's nodes must follow
};

/// Walks the last and the current casters (both in entity order) side by side and lists in
/// `changed` the boxes each changed caster left and took (see `SceneGeometry::changed`).
CasterDiff diffCasters(const std::vector<BoundedEntity>& last, const std::vector<BoundedEntity>& now,
                       std::vector<BoundedEntity>& changed) {
    changed.clear();
    CasterDiff diff;
    std::size_t i = 0;
    std::size_t j = 0;
    while (i < last.size() || j < now.size()) {
        if (j == now.size() || (i < last.size() && last[i].entity < now[j].entity)) {
            changed.push_back(last[i++]);  // gone
            diff.sameEntities = false;
        } else if (i == last.size() || now[j].entity < last[i].entity) {
            changed.push_back(now[j++]);  // new
            diff.sameEntities = false;
        } else {
            const bool boundsMoved = !(last[i].bounds == now[j].bounds);
            if (boundsMoved || now[j].moved || now[j].version != last[i].version) {
                changed.push_back(last[i]);  // left (the same box when it moved within its bounds)
                changed.push_back(now[j]);   // took
            }
            diff.boundsMoved = diff.boundsMoved || boundsMoved;
            ++i;
            ++j;
        }
    }
    return diff;
}

}  // namespace

void gatherGeometry(const World& world, SceneGeometry& out) {
    std::swap(out.casters, out.lastCasters);
    std::swap(out.receiverBoxes, out.lastReceiverBoxes);
    std::swap(out.backgrounds, out.lastBackgrounds);
    const DAabb lastEverything = out.everything;
    out.casters.clear();
    out.receiverBoxes.clear();
    out.backgrounds.clear();
    out.visible.measured = false;
    out.receivers = DAabb{};
    out.everything = DAabb{};
    world.view<Mesh, WorldTransform, WorldBounds>().each(
        [&](Entity e, const Mesh& mesh, const WorldTransform& wt, const WorldBounds& wb) {
            // A mesh with no triangles draws nothing: it must not widen any layer's fit either.
            if (!wt.finite || wb.box.empty() || mesh.data == nullptr || mesh.data->indices.empty()) return;
            out.everything.extend(wb.box);
            if (mesh.castShadows) out.casters.push_back({e, wb.box, false, wt.version});
            if (mesh.receiveShadows) {
                out.receiverBoxes.push_back(wb.box);
                out.receivers.extend(wb.box);
                if (!mesh.castShadows) out.backgrounds.push_back({e, wb.box, false, wt.version});
            }
        });
    // The game's own casters: bounds from their object bounds, as updateTransforms does for meshes.
    world.view<ShadowCasterDraw, WorldTransform>().each(
        [&](Entity e, const ShadowCasterDraw& c, const WorldTransform& wt) {
            if (!wt.finite || !c.drawsSomething() || c.localBounds.empty()) return;
            const DAabb box = transformBounds(wt.worldFromLocal, c.localBounds);
            out.everything.extend(box);
            out.casters.push_back({e, box, c.changedThisFrame, wt.version});
        });
    // Views walk back to front; entity order keeps caster lists comparable frame to frame.
    inEntityOrder(out.casters);
    inEntityOrder(out.backgrounds);

    out.receiversChanged = out.receiverBoxes != out.lastReceiverBoxes;
    out.backgroundsChanged =
        !std::equal(out.backgrounds.begin(), out.backgrounds.end(), out.lastBackgrounds.begin(),
                    out.lastBackgrounds.end(), [](const BoundedEntity& a, const BoundedEntity& b) {
                        return a.entity == b.entity && a.bounds == b.bounds && a.version == b.version;
                    });
    out.everythingChanged = !(out.everything == lastEverything);
    const CasterDiff diff = diffCasters(out.lastCasters, out.casters, out.changed);
    if (out.casters.size() < kIndexedItems) {
        out.casterTree.clear();
    } else if (!diff.sameEntities || out.casterTree.size() != out.casters.size()) {
        out.casterTree.build(out.casters);
    } else if (diff.boundsMoved) {
        out.casterTree.refit(out.casters);
    }
    if (out.changed.size() < kIndexedItems) {
        out.changedTree.clear();
    } else {
        out.changedTree.build(out.changed);
    }
}

}  // namespace shadow
