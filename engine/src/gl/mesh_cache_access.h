// The engine's own way into a `MeshCache` from inside a pass: the pass has read the host's
// pending GL errors already, so a draw does not ask for them again (glGetError can wait for a
// threaded driver).
#pragma once

#include <shadow/mesh_cache.h>

#include <cstddef>
#include <memory>
#include <vector>

namespace shadow::gpu {

/// What the engine's passes call on a `MeshCache`.
struct MeshCacheAccess {
    /// `MeshCache::bind` without reading the host's errors.
    static int bind(MeshCache& cache, const std::shared_ptr<const MeshData>& mesh) { return cache.bindInPass(mesh); }
    /// `MeshCache::collect` without reading the host's errors.
    static std::size_t collect(MeshCache& cache) { return cache.collectInPass(); }
    /// The cache's pending warnings (`MeshCache::warnings`), to move into a frame's stats.
    static std::vector<Warning>& pending(MeshCache& cache) { return cache.pending(); }
};

}  // namespace shadow::gpu
