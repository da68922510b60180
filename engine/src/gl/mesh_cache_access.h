// The engine's own way into a `MeshCache` from inside a pass: the pass has read the host's
// pending GL errors already, so a draw does not ask for them again (glGetError can wait for a
// threaded driver).
#pragma once

#include <shadow/mesh_cache.h>

#include "gl/gl_api.h"

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

namespace shadow::gpu {

/// How a draw deforms its mesh, as bits: which of shaders/mesh_vertex.glsl's deformations its
/// program compiles in (a rigid draw's program has neither).
enum MeshDeformBits : unsigned {
    kDeformSkinned = 1u,  ///< SG_SKINNED: a posed `Skin`
    kDeformMorphed = 2u,  ///< SG_MORPHED: a `Morph` with targets drawn
};
/// The kinds of deformation, 0 (rigid) to kDeformSkinned | kDeformMorphed: the size of a
/// program table indexed by them.
inline constexpr std::size_t kMeshDeforms = 4;

/// The deformation of a draw with `skin` and `morph` (each may be null); a morph with no target
/// drawn (every weight 0) is rigid.
[[nodiscard]] inline unsigned meshDeform(const Skin* skin, const Morph* morph) {
    return (skin != nullptr ? kDeformSkinned : 0u) | (morph != nullptr && !morph->drawn.empty() ? kDeformMorphed : 0u);
}

/// The `#define`s of a program compiled for `deform`, appended to `defines`.
inline void appendDeformDefines(unsigned deform, std::vector<std::string>& defines) {
    if ((deform & kDeformSkinned) != 0) defines.emplace_back("SG_SKINNED");
    if ((deform & kDeformMorphed) != 0) defines.emplace_back("SG_MORPHED");
}

/// The GL label suffix of a program compiled for `deform`: "", "/skinned", "/morphed", ...
inline std::string deformLabel(unsigned deform) {
    return std::string((deform & kDeformSkinned) != 0 ? "/skinned" : "") +
           ((deform & kDeformMorphed) != 0 ? "/morphed" : "");
}

/// A mesh program's uniforms of morph targets (shaders/mesh_vertex.glsl); -1 where the program
/// has none (one not built for kDeformMorphed).
struct DeformUniforms {
    GLint morphCount = -1;
    GLint morphTargets = -1;
    GLint morphInfluences = -1;
    /// The locations in `program`.
    [[nodiscard]] static DeformUniforms of(GLuint program);
};

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
    /// Draws `mesh` with `program` (built for `meshDeform(skin, morph)`) next: binds it and
    /// returns its index count, with its deformation (each may be null) set in `program` and
    /// bound: a posed skin's joint matrices (SG_BINDING_JOINTS), a morph's drawn targets (their
    /// displacements at SG_BINDING_MORPH_DELTAS). A rigid draw, or a morph with no target drawn,
    /// binds nothing.
    static int bindDeformed(MeshCache& cache, const std::shared_ptr<const MeshData>& mesh, GLuint program,
                            const DeformUniforms& uniforms, const Skin* skin, const Morph* morph);
    /// `MeshCache::collect` without reading the host's errors.
    static std::size_t collect(MeshCache& cache) { return cache.collectInPass(); }
    /// The cache's pending warnings (`MeshCache::warnings`), to move into a frame's stats.
    static std::vector<Warning>& pending(MeshCache& cache) { return cache.pending(); }
};

}  // namespace shadow::gpu
