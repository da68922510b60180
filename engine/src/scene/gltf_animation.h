// glTF animations to per-node `Animation` components.
#pragma once

#include <shadow/components.h>
#include <shadow/result.h>
#include <tiny_gltf.h>

#include <vector>

namespace shadow::gltf {

/// The keyframed channels of every glTF animation, gathered per target node (the result has
/// one entry per node; nodes nobody animates have no channels). Channels targeting
/// translation, rotation or scale are kept, others (morph `weights`, extension paths) are
/// ignored. A node's `duration` is the longest last key time of the glTF animations that
/// target it, so all channels of one glTF animation loop together.
///
/// Checked: sampler and node indices, interpolation names, key times finite and strictly
/// increasing, output counts (three per key for CUBICSPLINE), finite values.
[[nodiscard]] Result<std::vector<Animation>> importAnimations(const tinygltf::Model& model);

}  // namespace shadow::gltf
