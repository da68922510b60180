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
    /// Binds a material's texture (white for none) to texture unit `unit`: colour (sRGB, read
    /// linear) unless `srgb` is false (data: metallic-roughness, normals, occlusion).
    static void bindTexture(MeshCache& cache, const std::shared_ptr<const shadow::Texture>& texture, unsigned unit,
                            bool srgb = true) {
        cache.bindTextureInPass(texture, unit, srgb);
    }
    /// Binds a posed skin's joint matrices for the next draw (SG_BINDING_JOINTS).
    static void bindSkin(MeshCache& cache, const Skin& skin) { cache.bindSkinInPass(skin); }
    /// `MeshCache::collect` without reading the host's errors.
    static std::size_t collect(MeshCache& cache) { return cache.collectInPass(); }
    /// The cache's pending warnings (`MeshCache::warnings`), to move into a frame's stats.
    static std::vector<Warning>& pending(MeshCache& cache) { return cache.pending(); }
};

}  // namespace shadow::gpu
