// Constants shared by the C++ engine and the GLSL shaders: the one source of truth for both.
// Only preprocessor lines and comments may stand here, since C++ and GLSL both include this file.
#ifndef SG_SHARED_CONSTANTS_H
#define SG_SHARED_CONSTANTS_H

// Light types (LightType in components.h, in the same order).
#define SG_LIGHT_DIRECTIONAL 0
#define SG_LIGHT_SPOT 1
#define SG_LIGHT_POINT 2

// Shadow techniques (ShadowTechnique in components.h, in the same order).
#define SG_TECH_NONE 0
#define SG_TECH_HARD 1
#define SG_TECH_PCF 2
#define SG_TECH_PCSS 3
#define SG_TECH_PCSS_TEXTBOOK 4
#define SG_TECH_VSM 5
#define SG_TECH_VSSM 6
#define SG_TECH_MSM 7
#define SG_TECH_MSM_SOFT 8
#define SG_TECH_SDF 9

// Filter kernels (FilterKernel in components.h, in the same order).
#define SG_KERNEL_VOGEL 0
#define SG_KERNEL_POISSON 1
#define SG_KERNEL_UNIFORM 2

// Lights shaded by one main pass; more lights are added by further additive passes.
#define SG_MAX_LIGHTS_PER_PASS 8
// Layers of one light's shadow-map array: up to 4 cascades, or 6 cube faces.
#define SG_MAX_CASCADES 4
#define SG_MAX_LAYERS_PER_LIGHT 6
// Largest filter tap counts a light may ask for.
#define SG_MAX_SAMPLES 64

// Where the shadow GLSL reads its inputs: uniform-buffer binding points and texture units. A
// game's shader may define any of these before including the shadow GLSL (shadow_shaders.h,
// `ShadowBindingPoints`); the engine's own passes use these defaults.
#ifndef SG_BINDING_LIGHTS
#define SG_BINDING_LIGHTS 0
#endif
#ifndef SG_BINDING_LAYERS
#define SG_BINDING_LAYERS 1
#endif
// The filter kernels' sample points (Poisson disk), one block shared by every pass.
#ifndef SG_BINDING_KERNELS
#define SG_BINDING_KERNELS 2
#endif
// Texture units: the comparison sampler of pass slot i is unit SG_UNIT_SHADOW_COMPARE + i, the
// raw-depth sampler (PCSS blocker search) is unit SG_UNIT_SHADOW_DEPTH + i.
#ifndef SG_UNIT_SHADOW_COMPARE
#define SG_UNIT_SHADOW_COMPARE 0
#endif
#ifndef SG_UNIT_SHADOW_DEPTH
#define SG_UNIT_SHADOW_DEPTH 8
#endif
// The min/max depth pyramid of pass slot i (PCF and PCSS lights) is unit SG_UNIT_SHADOW_MINMAX + i.
#ifndef SG_UNIT_SHADOW_MINMAX
#define SG_UNIT_SHADOW_MINMAX 16
#endif
// The distance-field technique (sdf): the atlas of every caster's signed distance field (a 3D
// texture, one brick per mesh) and the instance records of the frame's field casters (a buffer
// texture of SG_SDF_INSTANCE_TEXELS vec4 per instance, layout in shaders/shadow_sdf.glsl).
#ifndef SG_UNIT_SDF_ATLAS
#define SG_UNIT_SDF_ATLAS 26
#endif
#ifndef SG_UNIT_SDF_INSTANCES
#define SG_UNIT_SDF_INSTANCES 27
#endif
#define SG_SDF_INSTANCE_TEXELS 9
// Most field casters one pixel's march reads: the nearest of those whose bounds its ray meets.
#define SG_SDF_MAX_NEAR 8
// Field casters of a light grouped under one bounding sphere, which a ray tests first.
#define SG_SDF_CLUSTER 16

// The module's own mesh programs (main pass, shadow pass): a material's base-colour texture's
// unit, the shader-storage binding of a skinned mesh's joint matrices.
#define SG_UNIT_BASE_COLOR 28
#define SG_BINDING_JOINTS 3
// A morphed mesh's target displacements (shaders/mesh_vertex.glsl), and the most targets one draw
// blends (kMaxMorphInfluences).
#define SG_BINDING_MORPH_DELTAS 4
// Technique auto's edge counts (shaders/lit.frag.glsl, SG_COUNT_EDGES): three per pass slot.
#define SG_BINDING_EDGE_COUNTS 5
// Width of the lit and umbra classes at the ends of [0, 1]: the error metrics' classes
// (kVisibilityClassEpsilon, shadow/metrics.h) and the edge counts' "neither 0 nor 1".
#define SG_VISIBILITY_CLASS_EPSILON 1e-3
#define SG_MAX_MORPH_INFLUENCES 16
// A material's other maps (shaders/material.glsl). Only the forward lit pass and the stage's
// surface pass read them, and neither reads the stage's targets nor the mask's inputs: they
// take those units (the forward lit pass binds the shadow units 0-23, the distance-field
// units 26-27 and the base colour 28 beside them).
#define SG_UNIT_METALLIC_ROUGHNESS 24
#define SG_UNIT_NORMAL_MAP 25
#define SG_UNIT_OCCLUSION 29
#define SG_UNIT_EMISSIVE 30

// Units the shadow mask reads the game's depth and normal textures from (after the three arrays).
#define SG_UNIT_MASK_DEPTH 24
#define SG_UNIT_MASK_NORMAL 25
// Lights one shadow mask holds: one per channel.
#define SG_MAX_MASK_LIGHTS 4
// A mask at reduced resolution (ShadowMaskRequest::resolution): its samples' visibility and
// camera-relative positions, read by its resolve (units no technique's code reads).
#define SG_UNIT_MASK_STAGE 31
#define SG_UNIT_MASK_STAGE_POSITION 29

// The renderer's screen-space visibility stage (RenderOptions::screenVisibility): units of its
// surface targets (shaders/screen_gbuffer.glsl: the surface's depth, coverage and normals; its
// material) and of the per-light visibility it resolves, read by the stage's passes and the
// deferred lit pass. The stage and the lit pass bind the shadow units too: these take the units
// above them.
#define SG_UNIT_GBUFFER_SURFACE 24
#define SG_UNIT_GBUFFER_MATERIAL 25
#define SG_UNIT_SCREEN_VISIBILITY 31
// With materials that have normal maps or emit (RenderOptions' frame holds one), the surface
// pass also stores the lighting normal and the emitted radiance, which only the deferred lit
// pass reads: it reads no material map, so this takes the emission map's unit.
#define SG_UNIT_GBUFFER_EXTRA 30
// The reduced-resolution stage's sample depths, read by its resolve.
#define SG_UNIT_SCREEN_DEPTH 29
// The reduced-resolution stage's visibility as the deferred lit pass reads it when it resolves
// the stage itself (its own units: the pass also reads the full-resolution visibility of the
// groups it does not resolve, and may refine with any technique, sdf's units included).
#define SG_UNIT_LIT_STAGE 28

// Unit the pyramid builder reads its source from.
#define SG_UNIT_MINMAX_SOURCE 0
// Image unit the pyramid builder writes a level through.
#define SG_IMAGE_MINMAX 0

// Texels of the shadow map along one edge of a tile of the min/max pyramid's level 0.
#define SG_MINMAX_TILE 4

// Vertex attributes of the module's meshes (shaders/mesh_vertex.glsl; the mesh cache's streams).
#define SG_ATTRIB_TEXCOORD1 5
#define SG_ATTRIB_TANGENT 6

// Fragment outputs of the main pass.
#define SG_OUT_COLOR 0
#define SG_OUT_POSITION 1
#define SG_OUT_DEPTH 2
#define SG_OUT_VISIBILITY0 3
#define SG_OUT_VISIBILITY1 4
// The deferred lit pass that resolves the stage itself: the slots it leaves to its correction
// (shaders/lit.frag.glsl, a bit each, R8UI).
#define SG_OUT_MARKS 5

// Debug views of the main pass (--debug NAME).
#define SG_DEBUG_NONE 0
#define SG_DEBUG_CASCADE 1
#define SG_DEBUG_BLOCKER_DEPTH 2
#define SG_DEBUG_PENUMBRA 3
#define SG_DEBUG_VISIBILITY 4
#define SG_DEBUG_MARCH_STEPS 5
#define SG_DEBUG_CLOSEST 6

#endif
