// GPU copies of the scene's meshes, shared by the shadow passes and the main pass. It sits below
// both: the shadow subsystem and the renderer use it, neither owns it.
#pragma once

#include <shadow/result.h>
#include <shadow/scene.h>

#include <cstddef>
#include <memory>

namespace shadow {

/// Each `MeshData` is uploaded once, on first use, and kept while its `MeshData` lives: the
/// GPU copies of meshes no longer alive are freed by `collect`, which `ShadowSystem::render`
/// calls once a frame (once: a cache shared with the renderer is not walked twice).
/// Requires a current OpenGL 4.5 context with `loadGl` done; `bind` throws `GlError` when an
/// upload fails.
class MeshCache {
public:
    /// Throws `GlError` when `loadGl` has not run.
    MeshCache();
    /// For a game built without exceptions: the cache, or the error the constructor would throw.
    [[nodiscard]] static Result<std::unique_ptr<MeshCache>> create() noexcept;
    ~MeshCache();
    MeshCache(const MeshCache&) = delete;
    MeshCache& operator=(const MeshCache&) = delete;

    /// Binds the vertex array of `mesh` (uploading it on first use) and returns its index count.
    int bind(const std::shared_ptr<const MeshData>& mesh);
    /// Number of meshes held on the GPU.
    [[nodiscard]] std::size_t size() const;
    /// Frees the GPU copies of the meshes whose `MeshData` no longer exists; returns how many.
    std::size_t collect();

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace shadow
