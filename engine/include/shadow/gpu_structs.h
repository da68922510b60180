// Buffer layouts shared by the C++ engine and the GLSL shaders (uniform blocks, std140, whose
// layout of these structs is the same as std430). The including side
// defines SG_STRUCT, SG_END_STRUCT, SG_VEC3, SG_MAT4, SG_FLOAT and SG_INT first: GLSL as the
// plain GLSL types, C++ as glm types with std430 alignment (see engine/include/shadow/gpu_records.h).
// Every vec3 is followed by one scalar so that the layout has no hidden padding.
#ifndef SG_STRUCT
#error \
    "shadow/gpu_structs.h lists the GPU records through macros: include shadow/gpu_records.h (C++) or shadow_types.glsl (GLSL)"
#endif

// One light of a pass. Positions are camera-relative world space (cs = world - camera).
SG_STRUCT(GpuLight)
SG_VEC3 csPosition;     // point/spot position (m)
SG_INT type;            // SG_LIGHT_*
SG_VEC3 wsDirection;    // unit direction the light travels (node -Z)
SG_FLOAT range;         // m; 0 = infinite
SG_VEC3 radiance;       // color * intensity
SG_FLOAT emitterSize;   // spot/point: radius (m); directional: angular radius (rad)
SG_FLOAT cosOuter;      // spot: cos of the cut-off half-angle
SG_FLOAT cosInner;      // spot: cos of the full-intensity half-angle
SG_INT technique;       // SG_TECH_*
SG_INT layerCount;      // layers of this light's array: cascades, 1, or 6
SG_FLOAT constantBias;  // m, plus constantBiasTexels texel footprints
SG_FLOAT slopeBias;     // texels
SG_FLOAT normalOffset;  // texels
SG_FLOAT pcfRadius;     // m at the receiver, at least pcfRadiusTexels texel footprints
SG_INT pcfSamples;
SG_INT blockerSamples;
SG_FLOAT maxFilterTexels;
SG_FLOAT mapSize;              // texels per layer edge
SG_INT firstLayer;             // index of layer 0 in the layer buffer
SG_FLOAT cascadeBlend;         // directional: fraction of a cascade's range blended into the next
SG_INT kernel;                 // SG_KERNEL_*
SG_FLOAT lightBleedReduction;  // VSM, VSSM: Chebyshev bounds below it read as shadow
SG_INT sdfFirst;               // sdf: its first field caster in the instance buffer
SG_INT sdfCount;               // sdf: its field casters
SG_INT sdfSteps;               // sdf: most march steps
SG_FLOAT sdfStartOffset;       // sdf: m along the normal and the ray before the march starts
SG_FLOAT sdfMinStep;           // sdf: shortest step (m)
SG_INT sdfClusterFirst;        // sdf: its first cluster of SG_SDF_CLUSTER field casters
SG_INT regionTest;             // PCF, PCSS: 1 when the lookups read the min/max pyramid, 0 when it was not built
SG_FLOAT constantBiasTexels;   // texel footprints added to constantBias (Shadow::constantBias automatic)
SG_FLOAT pcfRadiusTexels;      // least radius in texel footprints (Shadow::pcfRadius automatic)
SG_INT sdfMapCasters;          // sdf: 1 when some caster of its layers casts through the map (no field)
SG_FLOAT reserved3;
SG_END_STRUCT

// One layer (cascade, spot map or cube face) of a light's shadow-map array.
SG_STRUCT(GpuShadowLayer)
SG_MAT4 lightFromCs;     // camera-relative world -> light view (m; the light looks down -Z)
SG_MAT4 clipFromLight;   // light view -> clip
SG_FLOAT depthScale;     // stored depth = lsDepth / depthScale
SG_FLOAT depthNear;      // near plane of the projection (m)
SG_FLOAT splitFar;       // directional: camera distance where this cascade ends (m)
SG_INT orthographic;     // 1 for directional lights
SG_FLOAT momentScale;    // VSSM: its summed-area table holds the moments of min(z momentScale, 1) (0: no table)
SG_FLOAT blockerNear;    // the nearest a blocker can be (m; ShadowLayerPlan::blockerNear)
SG_INT chainFirstLevel;  // VSM, MSM-soft: the lowest level of the moment chain built (ShadowLayerPlan)
SG_INT chainLastLevel;   // VSM: the highest level of the moment chain built (ShadowLayerPlan)
SG_END_STRUCT
