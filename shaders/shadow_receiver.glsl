// The receiver as one light sees it: layer choice, normal offset, bias, the tangent plane the
// filter taps lie on, and the projection of a tap into a layer.
//
// Frame of reference (design.md): depths are linear metres from the light (perspective
// layers) or along its axis (orthographic layers). Filter radii are lateral distances in
// metres at the receiver, measured perpendicular to the light ray. A tap at lateral offset o
// is placed on the receiver's tangent plane along the light ray, so its reference depth is the
// plane's own depth there (receiver-plane depth bias, exact for planar receivers), and it is
// projected into whichever layer it lands in, which makes point-light filtering seamless
// across cube faces.
//
// References: J. Isidoro, "Shadow Mapping: GPU-based Tips and Techniques", GDC 2006
// (receiver-plane bias).
#ifndef SG_SHADOW_RECEIVER
#define SG_SHADOW_RECEIVER
#include "shadow_bindings.glsl"
#include "shadow_common.glsl"

// Steepest receiver slope (tan of the angle between normal and light) the bias follows;
// beyond it, at grazing light, the normal offset does the work.
const float kMaxSlope = 16.0;
// Steepest slope the tangent-plane taps follow exactly: tan(89.9 deg), so the filters see the
// receiver's own plane down to 0.1 degree of elevation. A tap at lateral offset o moves o * slope
// along the ray, and a plane flattened to a lesser slope puts the taps towards the light behind
// the receiver (tests/stability/grazing_light_test.cpp holds the open plane lit down to 0.5
// degrees). The clamp only keeps the stretch finite where cos(theta) loses its precision: n.L
// carries ~1e-6 of float error, so a slope of 573 errs by 573^2 * 1e-6 * 32 = 10 texels of depth
// at the widest filter (32 texels), inside the 24 texels the slope bias gives.
const float kMaxPlaneSlope = 573.0;
// Relative float error allowed for the two depths a tap compares, 2^-18 (32 ulps of a float:
// matrix products and interpolation each add a few). Measured: one ulp already clears the
// open-plane acne of a light straight above with no constant bias; 32 is the margin.
const float kDepthPrecision = 1.0 / 262144.0;

// The receiver as seen from one light.
struct Receiver {
    vec3 csPosition;  // camera-relative, after the normal offset
    vec3 toLight;     // unit direction from the receiver towards the light
    vec3 csTangent1;  // lateral axes (perpendicular to the light ray), stretched onto the
    vec3 csTangent2;  // receiver's tangent plane: a lateral offset o lands at o.x*t1 + o.y*t2
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
    bool orthographic;
};

// Where a world point falls in a layer.
struct Tap {
    int layer;
    vec2 uv;
    float depth;  // lsDepth (m) of the point
};

// Cube face (+X,-X,+Y,-Y,+Z,-Z) containing the direction `d`.
int cubeFace(vec3 d) {
    vec3 a = abs(d);
    if (a.x >= a.y && a.x >= a.z) return d.x >= 0.0 ? 0 : 1;
    if (a.y >= a.z) return d.y >= 0.0 ? 2 : 3;
    return d.z >= 0.0 ? 4 : 5;
}

Tap projectTap(GpuLight L, int layer, vec3 csPoint) {
    GpuShadowLayer S = uLayers[L.firstLayer + layer];
    vec3 ls = (S.lightFromCs * vec4(csPoint, 1.0)).xyz;
    vec4 clip = S.clipFromLight * vec4(ls, 1.0);
    Tap t;
    t.layer = layer;
    t.uv = clip.xy / max(clip.w, 1e-20) * 0.5 + 0.5;
    t.depth = lightSpaceDepth(ls, L.type == SG_LIGHT_DIRECTIONAL);
    return t;
}

// Layer of a directional light's cascades for a receiver at camera distance `viewDistance`.
int selectCascade(GpuLight L, float viewDistance) {
    for (int k = 0; k < L.layerCount - 1; ++k) {
        if (viewDistance < uLayers[L.firstLayer + k].splitFar) return k;
    }
    return L.layerCount - 1;
}

int selectLayer(GpuLight L, vec3 csPosition, float viewDistance) {
    if (L.type == SG_LIGHT_POINT) return cubeFace(csPosition - L.csPosition);
    if (L.type == SG_LIGHT_DIRECTIONAL) return selectCascade(L, viewDistance);
    return 0;
}

// World size of one texel of `layer` at the point `csPoint`.
float texelMetresAt(GpuLight L, int layer, vec3 csPoint) {
    GpuShadowLayer S = uLayers[L.firstLayer + layer];
    float scale = 2.0 / (S.clipFromLight[0][0] * L.mapSize);
    if (L.type == SG_LIGHT_DIRECTIONAL) return scale;
    float axial = -(S.lightFromCs * vec4(csPoint, 1.0)).z;
    return scale * max(axial, 0.0);
}

// The receiver for `layer` of a directional light's cascades, or, with layer < 0, for the
// layer the position selects (cube face, or the cascade of `viewDistance`).
Receiver makeReceiver(GpuLight L, vec3 csPosition, vec3 wsNormal, float viewDistance, int layer) {
    Receiver r;
    vec3 toLight = L.type == SG_LIGHT_DIRECTIONAL ? -L.wsDirection
                                                  : safeNormalize(L.csPosition - csPosition, -L.wsDirection);
    float cosTheta = clamp(dot(wsNormal, toLight), -1.0, 1.0);
    float sinTheta = sqrt(max(1.0 - cosTheta * cosTheta, 0.0));
    r.slope = min(sinTheta / max(abs(cosTheta), 1e-4), kMaxSlope);

    bool chosen = layer >= 0;
    if (!chosen) layer = selectLayer(L, csPosition, viewDistance);
    float texel = texelMetresAt(L, layer, csPosition);
    // Normal offset: move along the normal by whole texel footprints, more as the light grazes.
    r.offsetPerTexel = wsNormal * (L.normalOffset * sinTheta);
    r.csPosition = csPosition + r.offsetPerTexel * texel;
    r.toLight = L.type == SG_LIGHT_DIRECTIONAL ? toLight : safeNormalize(L.csPosition - r.csPosition, toLight);
    r.layer = chosen ? layer : selectLayer(L, r.csPosition, viewDistance);
    r.texelMetres = texelMetresAt(L, r.layer, r.csPosition);
    // Float error of the depths compared: both come from float positions of magnitude |cs| (the
    // receiver from the camera) and |ls| (the point from the layer's origin), good to a few ulps.
    vec3 ls = (uLayers[L.firstLayer + r.layer].lightFromCs * vec4(r.csPosition, 1.0)).xyz;
    float floatError = kDepthPrecision * (length(ls) + length(r.csPosition));
    r.depthBias = L.constantBias + L.slopeBias * r.texelMetres * r.slope + floatError;

    // Lateral axes perpendicular to the ray, then slid along the ray onto the tangent plane.
    vec3 a = abs(r.toLight);
    vec3 helper = (a.x <= a.y && a.x <= a.z) ? vec3(1, 0, 0) : (a.y <= a.z ? vec3(0, 1, 0) : vec3(0, 0, 1));
    vec3 t1 = normalize(cross(r.toLight, helper));
    vec3 t2 = cross(r.toLight, t1);
    float nDotL = dot(wsNormal, r.toLight);
    // Keep the stretch finite at grazing light: beyond kMaxPlaneSlope the plane is treated as that steep.
    float denom = sign(nDotL) * max(abs(nDotL), 1.0 / sqrt(1.0 + kMaxPlaneSlope * kMaxPlaneSlope));
    if (denom == 0.0) denom = 1.0;
    r.csTangent1 = t1 - r.toLight * (dot(wsNormal, t1) / denom);
    r.csTangent2 = t2 - r.toLight * (dot(wsNormal, t2) / denom);
    r.depthSlope = length(vec2(dot(wsNormal, t1), dot(wsNormal, t2))) / abs(denom);

    GpuShadowLayer S = uLayers[L.firstLayer + r.layer];
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
    return r;
}

// The tap at lateral offset `offset` (m) from the receiver, on its tangent plane.
//
// Perspective texels grow with the distance from the light, and at grazing light a tap slides
// far along the ray (offset x slope): a tap beyond the receiver takes the normal offset of its
// own, larger texel, or the bilinear neighbours of a steep receiver reach above it (measured:
// a spot at 0.5 degrees read down to 0.95 on an open plane without this).
Tap lateralTap(GpuLight L, Receiver r, vec2 offset) {
    vec3 p = r.csPosition + r.csTangent1 * offset.x + r.csTangent2 * offset.y;
    int layer = L.type == SG_LIGHT_POINT ? cubeFace(p - L.csPosition) : r.layer;
    if (layer == r.layer) {
        // Fast path, every tap of directional and spot lights and most of a point light's:
        // the receiver's cached layer, one projection per tap.
        vec3 ls = r.lsPosition + r.lsTangent1 * offset.x + r.lsTangent2 * offset.y;
        vec4 clip = r.clipPosition + r.clipTangent1 * offset.x + r.clipTangent2 * offset.y;
        if (!r.orthographic) {
            float texels = max(r.texelPerAxial * max(-ls.z, 0.0) - r.texelMetres, 0.0);
            ls += r.lsOffsetPerTexel * texels;
            clip += r.clipOffsetPerTexel * texels;
        }
        Tap t;
        t.layer = layer;
        t.uv = clip.xy / max(clip.w, 1e-20) * 0.5 + 0.5;
        t.depth = lightSpaceDepth(ls, r.orthographic);
        return t;
    }
    // A point light's tap that crossed into another cube face.
    p += r.offsetPerTexel * max(texelMetresAt(L, layer, p) - r.texelMetres, 0.0);
    return projectTap(L, layer, p);
}

// 1 where the tap's point is lit, with the 2x2 bilinear PCF of the comparison sampler.
float compareTap(int slot, GpuLight L, Receiver r, Tap t) {
    float depthScale = t.layer == r.layer ? r.depthScale : uLayers[L.firstLayer + t.layer].depthScale;
    float reference = min((t.depth - r.depthBias) / depthScale, 1.0);
    return texture(uShadowCompare[slot], vec4(t.uv, float(t.layer), reference));
}

#endif
