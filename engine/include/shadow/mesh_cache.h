// GPU copies of the scene's meshes, shared by the shadow passes and the main pass. One owner
// collects it: the module's `Renderer` owns one (`Renderer::meshes`) and collects it in
// `Renderer::render`; a game without the renderer uses `ShadowSystem`'s own, which
// `ShadowSystem::render(world, stats)` collects, or makes one and calls `collect` once a frame
// itself. The shadow maps only draw from the cache they are handed.
#pragma once

#include <shadow/result.h>
#include <shadow/scene.h>
#include <shadow/warnings.h>

#include <cstddef>
#include <memory>
#include <vector>

namespace shadow {

namespace gpu {
struct MeshCacheAccess;
}

/// Each `MeshData` (and each material `Texture`) is uploaded once, on first use, and kept while its `MeshData` lives: the
/// GPU copies of meshes no longer alive are freed by `collect`, which the cache's owner calls once
/// a frame (see the header comment). Requires a current OpenGL 4.5 context with `loadGl` done;
/// `bind` throws `GlError` when an upload fails. An error the host left pending in the context
/// before the constructor, `bind` or `collect` (calls without a `FrameStats`) is read, cleared
/// and kept as a `HostGlError` warning in `warnings()` (at most 16 until cleared), never thrown;
/// the next shadow-map or renderer `render` drawing from the cache moves them into its stats.
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
    /// `HostGlError` warnings of the calls without a `FrameStats`, oldest first, until
    /// `clearWarnings` (or a `ShadowSystem::render` that moves them into its stats).
    [[nodiscard]] const std::vector<Warning>& warnings() const;
    /// Forgets the warnings read.
    void clearWarnings();

private:
    friend struct gpu::MeshCacheAccess;
    /// `bind` inside an engine pass, which has read the host's errors already.
    int bindInPass(const std::shared_ptr<const MeshData>& mesh);
    /// `collect` inside an engine call, which has read the host's errors already.
    std::size_t collectInPass();
    /// Binds `texture` (uploaded with mipmaps on first use, as sRGB colour or linear data) to
    /// texture unit `unit`; a 1x1 white texture for none.
    void bindTextureInPass(const std::shared_ptr<const Texture>& texture, unsigned unit, bool srgb);
    /// Uploads `skin`'s joint matrices and binds them to SG_BINDING_JOINTS for the next draw.
    void bindSkinInPass(const Skin& skin);
    /// Binds `mesh`'s morph-target displacements (uploaded on first use) to
    /// SG_BINDING_MORPH_DELTAS; `mesh` was bound by `bindInPass` before.
    void bindMorphInPass(const MeshData& mesh);
    /// The warnings `warnings` returns, for an engine call to move into its `FrameStats`.
    std::vector<Warning>& pending();

    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace shadow
