// glTF animations to per-node `Animation` components.
#pragma once

#include <shadow/components.h>
#include <shadow/result.h>
#include <tiny_gltf.h>

#include <string>
#include <utility>
#include <vector>

namespace shadow::gltf {

/// One glTF animation as read: its channels with the node each one moves.
struct ImportedClip {
    std::string name;                                                ///< the file's, or `animation<i>`
    double duration = 0.0;                                           ///< its last key time (s)
    std::vector<std::pair<std::size_t, AnimationChannel>> channels;  ///< (node, channel)
};

/// The keyframed channels of every glTF animation, one `ImportedClip` per animation in file
/// order. Channels targeting translation, rotation, scale or morph `weights` (of a node whose
/// mesh has morph targets) are kept, others (extension paths) are left out.
///
/// Checked: sampler and node indices, interpolation names, key times finite and strictly
/// increasing, output counts (three per key for CUBICSPLINE), finite values.
[[nodiscard]] Result<std::vector<ImportedClip>> importAnimations(const tinygltf::Model& model);

}  // namespace shadow::gltf
