// The receiver as one light sees it: layer choice, normal offset, bias, the tangent plane the
// filter taps lie on, and the projection of a tap into a layer.
//
// Frame of reference (docs/output_contract.md): depths are linear metres from the light (perspective
// layers) or along its axis (orthographic layers). Filter radii are lateral distances in
// metres at the receiver, measured perpendicular to the light ray. A tap at lateral offset o
// is placed on the plane of the receiver's triangle along the light ray (the tangent plane of the
// surface the map stored, not of the interpolated normal), so its reference depth is the
// plane's own depth there (receiver-plane depth bias, exact for planar receivers), and it is
// projected into whichever layer it lands in, which makes point-light filtering seamless
// across cube faces. Each of the 2x2 texels a tap reads is then compared with the receiver's
// own triangle plane at that texel's centre (the plane's depth is exact there: depth is affine
// in the map's texels for orthographic layers, 1/axial distance for perspective ones), so a
// plane needs no slope bias and no normal offset, and light no longer leaks into the umbra
// next to its caster.
//
// References: J. Isidoro, "Shadow Mapping: GPU-based Tips and Techniques", GDC 2006
// (receiver-plane bias).
#ifndef SG_SHADOW_RECEIVER
#define SG_SHADOW_RECEIVER
#include "shadow_bindings.glsl"
#include "shadow_common.glsl"

// Steepest receiver slope (tan of the angle between normal and light) the bias follows;
// beyond it, at grazing light, the normal offset does the work.
const float sg_kMaxSlope = 16.0;
// Steepest slope the tangent-plane taps follow exactly: tan(89.9 deg), so the filters see the
// receiver's own plane down to 0.1 degree of elevation. A tap at lateral offset o moves o * slope
// along the ray, and a plane flattened to a lesser slope puts the taps towards the light behind
// the receiver (tests/stability/grazing_light_test.cpp holds the open plane lit down to 0.5
// degrees). The clamp only keeps the stretch finite where cos(theta) loses its precision: n.L
// carries ~1e-6 of float error, so a slope of 573 errs by 573^2 * 1e-6 * 32 = 10 texels of depth
// at the widest filter (32 texels), inside the 24 texels the slope bias gives.
const float sg_kMaxPlaneSlope = 573.0;
// Relative float error allowed for the two depths a tap compares, 2^-18 (32 ulps of a float:
// matrix products and interpolation each add a few; docs/tuning.md has the measurement).
const float sg_kDepthPrecision = 1.0 / 262144.0;
// Each of the 2x2 texels a tap compares is compared with the receiver plane's depth at its own
// centre, so a plane needs no slope bias at all: what is left of `slopeBias` at the receiver,
// this fraction, covers the surface bending away from its triangle's plane within a texel or
// two: less leaves false shadow on curved receivers, more lets light into umbrae
// (docs/tuning.md; BENCHMARKS.md's umbra-leak table measures the result).
const float sg_kNearSlopeBias = 0.2;

// What a technique asks of its receiver: the part of the bias and of the normal offset that is
// its own (each technique's include defines its policy, e.g. sg_pcfPolicy()).
struct sg_ReceiverPolicy {
    float extraNormalOffset;  // texel footprints added to the light's normalOffset
    float slopeBiasShare;     // fraction of the light's slopeBias applied at the receiver
    float reachBias;          // m of depth bias per m of a tap's reach (x the ray's secant)
};

// The receiver policy of the filters that compare each texel with the receiver's own plane:
// only sg_kNearSlopeBias of the slope bias at the receiver, no extra offset, no reach bias.
sg_ReceiverPolicy sg_planePolicy() {
    return sg_ReceiverPolicy(0.0, sg_kNearSlopeBias, 0.0);
}

// The receiver as seen from one light.
struct sg_Receiver {
    vec3 csPosition;  // camera-relative, after the normal offset
    vec3 csNormal;    // the shading normal (unit)
    vec3 toLight;     // unit direction from the receiver towards the light
    vec3 csTangent1;  // lateral axes (perpendicular to the light ray), stretched onto the
    vec3 csTangent2;  // receiver triangle's plane: a lateral offset o lands at o.x*t1 + o.y*t2
    float slope;      // tan of the angle between normal and light, clamped
    int layer;        // layer for directional/spot lights (point lights choose per tap)
    float texelMetres;  // world size of one shadow texel at the receiver
    float depthBias;  // m, subtracted from every tap's reference depth
    vec3 offsetPerTexel;  // the normal offset per metre of texel footprint
    // The receiver's own layer, cached so that a tap in it costs one projection: light-space
    // position and tangents (the layer transform is affine, so a tap's light-space point is
    // lsPosition + o.x*lsTangent1 + o.y*lsTangent2), projection and depth scale.
    vec3 lsPosition;
    vec3 lsTangent1;
    vec3 lsTangent2;
    vec3 lsOffsetPerTexel;
    // The same in clip space (the projection is linear in homogeneous coordinates), so that a
    // tap's clip position costs three multiply-adds instead of a matrix product.
    vec4 clipPosition;
    vec4 clipTangent1;
    vec4 clipTangent2;
    vec4 clipOffsetPerTexel;
    float depthScale;
    float texelPerAxial;  // perspective: texel footprint per metre of axial distance
    float depthSlope;     // |change of a tap's depth| per lateral metre along the tangent plane
    // The receiver's geometric plane (its triangle's) in the receiver's layer: the change of its
    // linear depth (sg_planeDepthPerTexel) per texel step in s and t, so that each of the 2x2
    // texels a tap compares is compared with the plane's depth at that texel's own centre.
    vec2 refPerTexel;
    float reachBias;      // m of bias per m of a tap's reach from the receiver (sg_ReceiverPolicy)
    vec2 texelTan;    // perspective layers: change of a ray's lateral/axial ratio per texel
    vec3 csPlane;   // the normal of the plane the taps lie on (sg_tapPlaneNormal), for the other cube faces
    bool orthographic;
};

// Where a world point falls in a layer.
struct sg_Tap {
    int layer;
    vec2 uv;
    float depth;  // lsDepth (m) of the point
    float reach;  // lateral distance (m) from the receiver
    float axial;  // distance (m) along the layer's axis (perspective layers)
    vec2 rayTan;  // perspective layers: the tap's ray, lateral metres per axial metre
    vec2 refPerTexel;  // change of the receiver plane's linear depth per texel step
};

// Cube face (+X,-X,+Y,-Y,+Z,-Z) containing the direction `d`.
int sg_cubeFace(vec3 d) {
    vec3 a = abs(d);
    if (a.x >= a.y && a.x >= a.z) return d.x >= 0.0 ? 0 : 1;
    if (a.y >= a.z) return d.y >= 0.0 ? 2 : 3;
    return d.z >= 0.0 ? 4 : 5;
}

sg_Tap sg_projectTap(sg_GpuLight L, int layer, vec3 csPoint) {
    sg_GpuShadowLayer S = sg_layers[L.firstLayer + layer];
    vec3 ls = (S.lightFromCs * vec4(csPoint, 1.0)).xyz;
    vec4 clip = S.clipFromLight * vec4(ls, 1.0);
    sg_Tap t;
    t.layer = layer;
    t.uv = clip.xy / max(clip.w, 1e-20) * 0.5 + 0.5;
    t.depth = sg_lightSpaceDepth(ls, L.type == SG_LIGHT_DIRECTIONAL);
    t.axial = max(-ls.z, 1e-30);
    t.rayTan = ls.xy / t.axial;
    t.reach = 0.0;
    t.refPerTexel = vec2(0.0);
    return t;
}

// Layer of a directional light's cascades for a receiver at camera distance `viewDistance`: the
// first cascade whose split lies beyond it. A loop of constant length, which the compiler
// unrolls: a loop of the light's own cascade count would be one more loop in sequence in the
// driver's code (see sg_shadowVisibility).
int sg_selectCascade(sg_GpuLight L, float viewDistance) {
    int layer = L.layerCount - 1;
    for (int k = SG_MAX_CASCADES - 2; k >= 0; --k) {
        if (k < L.layerCount - 1 && viewDistance < sg_layers[L.firstLayer + k].splitFar) layer = k;
    }
    return layer;
}

int sg_selectLayer(sg_GpuLight L, vec3 csPosition, float viewDistance) {
    if (L.type == SG_LIGHT_POINT) return sg_cubeFace(csPosition - L.csPosition);
    if (L.type == SG_LIGHT_DIRECTIONAL) return sg_selectCascade(L, viewDistance);
    return 0;
}

// World size of one texel of `layer` at the point `csPoint`.
float sg_texelMetresAt(sg_GpuLight L, int layer, vec3 csPoint) {
    sg_GpuShadowLayer S = sg_layers[L.firstLayer + layer];
    float scale = 2.0 / (S.clipFromLight[0][0] * L.mapSize);
    if (L.type == SG_LIGHT_DIRECTIONAL) return scale;
    float axial = -(S.lightFromCs * vec4(csPoint, 1.0)).z;
    return scale * max(axial, 0.0);
}

// The normal of the plane the taps lie on: the unit plane normal `plane` with its component along
// the light ray held to at least that of a plane sg_kMaxPlaneSlope steep (sign kept), so that the
// taps' stretch stays finite at grazing light. The taps' tangents slide along the ray onto this
// plane (sg_makeReceiver), and its depth per texel (sg_planeDepthPerTexel) is theirs.
vec3 sg_tapPlaneNormal(vec3 plane, vec3 toLight) {
    float nDotL = dot(plane, toLight);
    float along = sign(nDotL) * max(abs(nDotL), 1.0 / sqrt(1.0 + sg_kMaxPlaneSlope * sg_kMaxPlaneSlope));
    if (along == 0.0) along = 1.0;
    return plane + toLight * (along - nDotL);
}

// The change per texel step (s, t) of a layer of the plane's linear depth (the quantity affine in
// the map's texels on a plane: the depth of an orthographic layer, the inverse of the axial
// distance of a perspective one; the depth itself is not, and at grazing light a linear
// extrapolation of it over one texel errs by more than the bias), for the plane with normal
// `lsNormal` through `ls` (both in the layer's light space), `texelTan` the layer's texel size
// (sg_Receiver::texelTan). In closed form, exact for a plane: where it meets the ray of map
// position (u, v) (lateral metres per axial metre), n.(u w, v w, -w) = n.p gives
// 1/w = (n.x u + n.y v - n.z) / n.p; an orthographic layer's depth -z is
// (n.x x + n.y y - n.p) / n.z. Zero where the plane holds the light ray.
vec2 sg_planeDepthPerTexel(vec3 ls, vec3 lsNormal, vec2 texelTan, bool orthographic) {
    float across = orthographic ? lsNormal.z : dot(lsNormal, ls);
    if (!(abs(across) > 0.0) || (!orthographic && !(ls.z < 0.0))) return vec2(0.0);
    return lsNormal.xy * texelTan / across;
}

// The receiver for `layer` of a directional light's cascades, or, with layer < 0, for the
// layer the position selects (cube face, or the cascade of `viewDistance`).
// `policy` is the technique's share of bias and offset.
sg_Receiver sg_makeReceiver(sg_GpuLight L, vec3 csPosition, vec3 wsNormal, vec3 geoNormal, float curvature, float viewDistance, int layer,
                            sg_ReceiverPolicy policy) {
    sg_Receiver r;
    vec3 toLight = L.type == SG_LIGHT_DIRECTIONAL ? -L.wsDirection
                                                  : sg_safeNormalize(L.csPosition - csPosition, -L.wsDirection);
    float cosTheta = clamp(dot(wsNormal, toLight), -1.0, 1.0);
    float sinTheta = sqrt(max(1.0 - cosTheta * cosTheta, 0.0));
    r.slope = min(sinTheta / max(abs(cosTheta), 1e-4), sg_kMaxSlope);
    // Along a slanted ray a surface's rise above its tangent plane is that many times deeper;
    // capped at 4 (76 degrees), beyond which the slope bias and the normal offset do the work.
    r.reachBias = policy.reachBias * min(sqrt(1.0 + r.slope * r.slope), 4.0);

    bool chosen = layer >= 0;
    if (!chosen) layer = sg_selectLayer(L, csPosition, viewDistance);
    float texel = sg_texelMetresAt(L, layer, csPosition);
    // Normal offset: move along the normal by whole texel footprints, more as the light grazes.
    r.offsetPerTexel = wsNormal * ((policy.extraNormalOffset + L.normalOffset) * sinTheta);
    r.csPosition = csPosition + r.offsetPerTexel * texel;
    r.csNormal = wsNormal;
    r.toLight = L.type == SG_LIGHT_DIRECTIONAL ? toLight : sg_safeNormalize(L.csPosition - r.csPosition, toLight);
    r.layer = chosen ? layer : sg_selectLayer(L, r.csPosition, viewDistance);
    r.texelMetres = sg_texelMetresAt(L, r.layer, r.csPosition);
    // Float error of the depths compared: both come from float positions of magnitude |cs| (the
    // receiver from the camera) and |ls| (the point from the layer's origin), good to a few ulps.
    vec3 ls = (sg_layers[L.firstLayer + r.layer].lightFromCs * vec4(r.csPosition, 1.0)).xyz;
    float floatError = sg_kDepthPrecision * (length(ls) + length(r.csPosition));
    r.depthBias = L.constantBias + L.constantBiasTexels * r.texelMetres + policy.slopeBiasShare * L.slopeBias * r.texelMetres * r.slope + floatError;

    // Lateral axes perpendicular to the ray, then slid along the ray onto the tangent plane.
    vec3 t1, t2;
    sg_perpendicularBasis(r.toLight, t1, t2);
    // The taps lie on the plane of the receiver's own triangle (turned to the shading normal's
    // side), not on the plane of its interpolated normal: those normals leave the triangles of a
    // smooth low-poly mesh by up to half a facet's angle, and taps on their plane are compared
    // with depths no triangle has, which darkens whole facets of the lit side
    // (tests/shadow/terminator_test.cpp: PCF's RMSE against the truth 0.034 -> 0.012 on a
    // 360-triangle sphere under a sun, 0.053 -> 0.013 under a spot).
    // Beyond sg_kMaxPlaneSlope the plane is treated as that steep (sg_tapPlaneNormal).
    vec3 planeNormal = dot(geoNormal, wsNormal) < 0.0 ? -geoNormal : geoNormal;
    r.csPlane = sg_tapPlaneNormal(planeNormal, r.toLight);
    float along = dot(r.csPlane, r.toLight);
    r.csTangent1 = t1 - r.toLight * (dot(r.csPlane, t1) / along);
    r.csTangent2 = t2 - r.toLight * (dot(r.csPlane, t2) / along);
    r.depthSlope = length(vec2(dot(r.csPlane, t1), dot(r.csPlane, t2))) / abs(along);

    sg_GpuShadowLayer S = sg_layers[L.firstLayer + r.layer];
    mat3 linear = mat3(S.lightFromCs);
    r.lsPosition = ls;
    r.lsTangent1 = linear * r.csTangent1;
    r.lsTangent2 = linear * r.csTangent2;
    r.lsOffsetPerTexel = linear * r.offsetPerTexel;
    r.clipPosition = S.clipFromLight * vec4(ls, 1.0);
    r.clipTangent1 = S.clipFromLight * vec4(r.lsTangent1, 0.0);
    r.clipTangent2 = S.clipFromLight * vec4(r.lsTangent2, 0.0);
    r.clipOffsetPerTexel = S.clipFromLight * vec4(r.lsOffsetPerTexel, 0.0);
    r.depthScale = S.depthScale;
    r.orthographic = L.type == SG_LIGHT_DIRECTIONAL;  // the layers of directional lights, only
    r.texelPerAxial = 2.0 / (S.clipFromLight[0][0] * L.mapSize);
    // Every perspective layer of a light has the same symmetric projection (spot, cube faces).
    r.texelTan = 2.0 / (vec2(S.clipFromLight[0][0], S.clipFromLight[1][1]) * float(L.mapSize));
    r.refPerTexel = sg_planeDepthPerTexel(ls, linear * r.csPlane, r.texelTan, r.orthographic);
    return r;
}

// The fixed filter radius (m) of PCF and VSM at the receiver: the light's `pcfRadius` in metres
// (set, or when automatic the penumbra of its emitter), at least `pcfRadiusTexels` texel
// footprints (0 when set), at most `maxFilterTexels` texels.
float sg_pcfRadius(sg_GpuLight L, sg_Receiver r) {
    return min(max(L.pcfRadius, L.pcfRadiusTexels * r.texelMetres), L.maxFilterTexels * r.texelMetres);
}

// The tap at the receiver itself: sg_receiverTap(r) without a lateral tap's
// arithmetic (it lies in the receiver's cached layer, at its own texel's footprint).
sg_Tap sg_receiverTap(sg_Receiver r) {
    sg_Tap t;
    t.layer = r.layer;
    t.uv = r.clipPosition.xy / max(r.clipPosition.w, 1e-20) * 0.5 + 0.5;
    t.depth = sg_lightSpaceDepth(r.lsPosition, r.orthographic);
    t.axial = max(-r.lsPosition.z, 1e-30);
    t.rayTan = r.lsPosition.xy / t.axial;
    t.reach = 0.0;
    t.refPerTexel = r.refPerTexel;
    return t;
}

// The tap at lateral offset `offset` (m) from the receiver, on its tangent plane.
//
// Perspective texels grow with the distance from the light, and at grazing light a tap slides
// far along the ray (offset x slope): a tap beyond the receiver takes the normal offset of its
// own, larger texel, or the bilinear neighbours of a steep receiver reach above it
// (tests/stability/grazing_light_test.cpp: a spot at 0.5 degrees on an open plane).
sg_Tap sg_lateralTap(sg_GpuLight L, sg_Receiver r, vec2 offset) {
    vec3 p = r.csPosition + r.csTangent1 * offset.x + r.csTangent2 * offset.y;
    int layer = L.type == SG_LIGHT_POINT ? sg_cubeFace(p - L.csPosition) : r.layer;
    // Every tap of directional and spot lights and most of a point light's lie in the receiver's
    // cached layer: one projection per tap.
    vec3 ls = r.lsPosition + r.lsTangent1 * offset.x + r.lsTangent2 * offset.y;
    vec4 clip = r.clipPosition + r.clipTangent1 * offset.x + r.clipTangent2 * offset.y;
    if (!r.orthographic) {
        float texels = max(r.texelPerAxial * max(-ls.z, 0.0) - r.texelMetres, 0.0);
        ls += r.lsOffsetPerTexel * texels;
        clip += r.clipOffsetPerTexel * texels;
    }
    sg_Tap t;
    t.layer = layer;
    t.uv = clip.xy / max(clip.w, 1e-20) * 0.5 + 0.5;
    t.depth = sg_lightSpaceDepth(ls, r.orthographic);
    t.axial = max(-ls.z, 1e-30);
    t.rayTan = ls.xy / t.axial;
    t.reach = length(offset);
    t.refPerTexel = r.refPerTexel;
    // A point light's tap that crossed into another cube face, projected into that face. A loop
    // of 0 or 1 trips rather than an `if`: a CPU rasteriser runs both sides of an `if`, but skips
    // a loop that no pixel of its SIMD group enters (BENCHMARKS.md, fragment costs).
    SG_ISOLATED
    for (int crossed = 0; crossed < int(layer != r.layer); ++crossed) {
        p += r.offsetPerTexel * max(sg_texelMetresAt(L, layer, p) - r.texelMetres, 0.0);
        t = sg_projectTap(L, layer, p);
        t.reach = length(offset);
        sg_GpuShadowLayer S = sg_layers[L.firstLayer + layer];
        t.refPerTexel = sg_planeDepthPerTexel((S.lightFromCs * vec4(p, 1.0)).xyz, mat3(S.lightFromCs) * r.csPlane,
                                              r.texelTan, false);
    }
    return t;
}

#endif
