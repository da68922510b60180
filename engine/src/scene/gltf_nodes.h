// glTF nodes: each node's transform and references checked, and the node graph's shape (a
// forest) and the chosen scene's roots worked out, before anything is instantiated.
#pragma once

#include <shadow/components.h>
#include <shadow/result.h>
#include <shadow/warnings.h>
#include <tiny_gltf.h>

#include <optional>
#include <vector>

namespace shadow::gltf {

/// What the importer needs of a node, checked.
struct NodeInfo {
    Transform transform;
    std::optional<std::size_t> light;
    /// The node's `matrix` has fewer than two non-zero columns: `transform.rotation` is the
    /// identity by default, not the file's (which it does not hold).
    bool rotationUndetermined = false;
};

/// `nodes[i]` checked: mesh and camera indices in range, the transform (TRS or an affine
/// `matrix`) finite, and the light it references (an index below `lightCount`).
[[nodiscard]] Result<NodeInfo> checkNode(const tinygltf::Model& model, std::size_t i, std::size_t lightCount);

/// Each node's parent (-1 for roots). The node graph must be a forest: children in range, no
/// node with two parents, no cycles.
[[nodiscard]] Result<std::vector<int>> nodeParents(const tinygltf::Model& model);

/// The root nodes to instantiate, in order: the file's `scene` (else scenes[0]) as it lists
/// them, or every root node in index order when the file has no scenes. A listed node that is
/// not a root (exporters write such files, and other engines load them) is taken once: below
/// its nearest ancestor the scene lists too, else as a root of its own subtree with its own
/// transform; a node listed twice is taken once. Each such listing is a `SceneNodeNotRoot`
/// warning naming the node.
[[nodiscard]] Result<std::vector<int>> sceneRoots(const tinygltf::Model& model, const std::vector<int>& parents,
                                                  std::vector<Warning>& warnings);

}  // namespace shadow::gltf
