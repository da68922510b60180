// The main pass's programs: the depth pre-pass, and the lit program specialised for each light
// configuration (`LitVariant`), compiled on first use and cached.
#pragma once

#include "gl/mesh_cache_access.h"
#include "gl/objects.h"
#include "render/light_packing.h"

#include <shadow/components.h>
#include <shadow/mesh_cache.h>

#include <map>
#include <string>

namespace shadow::render {

/// Uniform locations shared by the pre-pass and the lit programs (lit.vert.glsl).
struct MeshUniforms {
    GLint csFromLocal = -1, normalFromLocal = -1, clipFromCs = -1;
    gpu::DeformUniforms deform;
};

/// Uniform locations of a mesh's material (shaders/material.glsl), shared by the lit programs and
/// the surface pass's; those of the maps variant (SG_MATERIAL_MAPS) are -1 in the others.
struct MaterialUniforms {
    GLint receiveShadows = -1, albedo = -1, specular = -1, shininess = -1, metallic = -1, textured = -1;
    GLint emissive = -1;
    GLint baseFactor = -1, roughness = -1, normalScale = -1, occlusionStrength = -1;
    GLint mapUsed = -1, mapSet = -1, mapTransform = -1;
};

/// Sets `mesh`'s and `material`'s uniforms of `program` (each clamped to its documented range);
/// the textures are the caller's to bind (`bindMaterialTextures`).
void setMaterial(GLuint program, const MaterialUniforms& u, const Mesh& mesh, const Material& material);

/// Binds `material`'s textures on their units (SG_UNIT_BASE_COLOR and, with `maps`, the four of
/// the maps variant): white where it has none.
void bindMaterialTextures(MeshCache& meshes, const Material& material, bool maps);

/// A compiled lit variant and its uniform locations.
struct LitProgram {
    gpu::Program program;
    MeshUniforms mesh;
    MaterialUniforms material;
    GLint ambientSky = -1, ambientGround = -1, cameraForward = -1;
    GLint ray00 = -1, rayDx = -1, rayDy = -1;  ///< deferred: the pixels' rays (ScreenRays)
    GLint pixelAngle = -1;                     ///< deferred, resolving the stage: ScreenRays::pixelAngle
    GLint countSlots = -1, countBase = -1;     ///< SG_COUNT_EDGES: the slots counted, their first counter
};

/// A depth pre-pass program: the lit vertex shader and no fragment work, or (alpha-tested, for
/// cut-out materials) the alpha test alone.
struct DepthPrepassProgram {
    gpu::Program program;
    MeshUniforms mesh;
    GLint alpha = -1, alphaCutoff = -1;  ///< the alpha-tested program's
};

/// The GL label of a variant, e.g. "Main/Lit[spot:pcss,point:hard,AOV]".
std::string variantLabel(const LitVariant& variant);

/// `techniqueBit`s of the techniques a variant's lights use: the code its program compiles.
unsigned variantTechniques(const LitVariant& variant);

/// The `#define`s of a variant (see lit.frag.glsl).
std::vector<std::string> variantDefines(const LitVariant& variant);

/// The correction of group `group` (slots 4 `group` to 4 `group` + 3) of a deferred lit pass that
/// resolves it (`pass`, LitVariant::resolve): that group's slots alone, from SG_SLOT_BASE on (it
/// reads the lit pass's marks, not the stage: no divisor).
[[nodiscard]] LitVariant correctionVariant(const LitVariant& pass, int group);

/// Lit programs by variant, built on first use. Throws `GlError` when a variant does not build.
class LitProgramCache {
public:
    /// The program of `variant`; `compiled` is incremented when it had to be built.
    LitProgram& get(const LitVariant& variant, int& compiled);
    [[nodiscard]] std::size_t size() const { return programs_.size(); }

private:
    std::map<LitVariant, LitProgram> programs_;
};

/// The depth pre-pass's program, alpha-tested or not, for meshes deformed as `deform`
/// (gpu::MeshDeformBits) says.
DepthPrepassProgram buildDepthPrepass(bool alphaTested, unsigned deform = 0);

/// The screen-space visibility stage's surface pass (gbuffer.frag.glsl): the lit vertex shader,
/// the material's uniforms, and (alpha-tested, for cut-out materials) the alpha test.
struct SurfaceProgram {
    gpu::Program program;
    MeshUniforms mesh;
    MaterialUniforms material;
    GLint alpha = -1, alphaCutoff = -1, cameraForward = -1;
};

/// What a surface program is built for (each a bit of `SurfaceProgramKey`).
enum SurfaceProgramBits : unsigned {
    kSurfaceAlphaTested = 1u,      ///< SG_ALPHA_TESTED: a cut-out material
    kSurfaceMaps = 2u,             ///< SG_MATERIAL_MAPS: a material with maps
    kSurfaceMaterialTargets = 4u,  ///< SG_GBUFFER_MATERIAL: the frame stores lighting normal and emission
    kSurfaceTextured = 8u,         ///< SG_BASE_COLOR_TEXTURE: a material of the frame has a base-colour texture
    /// The bits above: the meshes' deformation (gpu::MeshDeformBits) times this.
    kSurfaceDeformUnit = 16u,
};
/// Surface programs by their bits: the size of a table of them.
inline constexpr std::size_t kSurfacePrograms = kSurfaceDeformUnit * gpu::kMeshDeforms;

SurfaceProgram buildSurfaceProgram(unsigned bits);

}  // namespace shadow::render
