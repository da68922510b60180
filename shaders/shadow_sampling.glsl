// Shadow visibility of one light at one receiver point: hard, PCF and PCSS from one source.
//
// Each technique is compiled only when its define is set (SG_TECH_HARD_ENABLED,
// SG_TECH_PCF_ENABLED, SG_TECH_PCSS_ENABLED); the renderer sets exactly the ones its lights use.
//
// Frame of reference (design.md): depths are linear metres from the light (perspective
// layers) or along its axis (orthographic layers). Filter radii are lateral distances in
// metres at the receiver, measured perpendicular to the light ray. A tap at lateral offset o
// is placed on the receiver's tangent plane along the light ray, so its reference depth is the
// plane's own depth there (receiver-plane depth bias, exact for planar receivers), and it is
// projected into whichever layer it lands in, which makes point-light filtering seamless
// across cube faces.
//
// References: W. Reeves, D. Salesin, R. Cook, "Rendering Antialiased Shadows with Depth Maps",
// SIGGRAPH 1987 (PCF); R. Fernando, "Percentage-Closer Soft Shadows", SIGGRAPH 2005 sketch
// (PCSS); J. Isidoro, "Shadow Mapping: GPU-based Tips and Techniques", GDC 2006 (receiver-plane
// bias); J. Jimenez, "Next Generation Post Processing in Call of Duty: Advanced Warfare",
// SIGGRAPH 2014 (interleaved gradient noise); H. Vogel, "A better way to construct the
// sunflower head", 1979 (golden-angle spiral).
#include "glsl_types.glsl"
#include "shadow_common.glsl"

layout(std430, binding = SG_BINDING_LIGHTS) readonly buffer LightBuffer {
    GpuLight uLights[];
};
layout(std430, binding = SG_BINDING_LAYERS) readonly buffer LayerBuffer {
    GpuShadowLayer uLayers[];
};

layout(binding = SG_UNIT_SHADOW_COMPARE) uniform sampler2DArrayShadow uShadowCompare[SG_MAX_LIGHTS_PER_PASS];
#if defined(SG_TECH_PCSS_ENABLED) || defined(SG_TECH_PCSS_TEXTBOOK_ENABLED)
layout(binding = SG_UNIT_SHADOW_DEPTH) uniform sampler2DArray uShadowDepth[SG_MAX_LIGHTS_PER_PASS];
#endif

const float kGoldenAngle = 2.39996323;
// Steepest receiver slope (tan of the angle between normal and light) the bias follows;
// beyond it, at grazing light, the normal offset does the work.
const float kMaxSlope = 16.0;
// Steepest slope the tangent-plane taps follow exactly: tan(89.9 deg), so the filters see the
// receiver's own plane down to 0.1 degree of elevation. A tap at lateral offset o moves o * slope
// along the ray, and a plane flattened to a lesser slope puts the taps towards the light behind
// the receiver (measured: at 0.5 degrees with the old clamp of 16, PCF read as low as 0.76 under
// a sun and 0.53 under a spot on an open plane). The clamp only keeps the stretch finite where cos(theta) loses its precision: n.L
// carries ~1e-6 of float error, so a slope of 573 errs by 573^2 * 1e-6 * 32 = 10 texels of depth
// at the widest filter (32 texels), inside the 24 texels the slope bias gives.
const float kMaxPlaneSlope = 573.0;
// Relative float error allowed for the two depths a tap compares, 2^-18 (32 ulps of a float:
// matrix products and interpolation each add a few). Measured: one ulp already clears the
// open-plane acne of a light straight above with no constant bias; 32 is the margin.
const float kDepthPrecision = 1.0 / 262144.0;

// Debug outputs of the last PCSS evaluation (--debug blocker / penumbra).
float gDebugBlockerDepth = 0.0;
float gDebugPenumbra = 0.0;
int gDebugCascade = 0;

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
    mat4 clipFromLight;
    float depthScale;
    float texelPerAxial;  // perspective: texel footprint per metre of axial distance
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
    vec3 ls = (S.lightFromWorld * vec4(csPoint, 1.0)).xyz;
    vec4 clip = S.clipFromLight * vec4(ls, 1.0);
    Tap t;
    t.layer = layer;
    t.uv = clip.xy / max(clip.w, 1e-20) * 0.5 + 0.5;
    t.depth = lightSpaceDepth(ls, S.orthographic != 0);
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
    if (S.orthographic != 0) return scale;
    float axial = -(S.lightFromWorld * vec4(csPoint, 1.0)).z;
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
    vec3 ls = (uLayers[L.firstLayer + r.layer].lightFromWorld * vec4(r.csPosition, 1.0)).xyz;
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

    GpuShadowLayer S = uLayers[L.firstLayer + r.layer];
    mat3 linear = mat3(S.lightFromWorld);
    r.lsPosition = ls;
    r.lsTangent1 = linear * r.csTangent1;
    r.lsTangent2 = linear * r.csTangent2;
    r.lsOffsetPerTexel = linear * r.offsetPerTexel;
    r.clipFromLight = S.clipFromLight;
    r.depthScale = S.depthScale;
    r.orthographic = S.orthographic != 0;
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
        if (!r.orthographic) ls += r.lsOffsetPerTexel * max(r.texelPerAxial * max(-ls.z, 0.0) - r.texelMetres, 0.0);
        vec4 clip = r.clipFromLight * vec4(ls, 1.0);
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

// Per-pixel rotation of the sample pattern, stable from frame to frame (Jimenez 2014).
float interleavedGradientNoise(vec2 pixel) {
    return fract(52.9829189 * fract(dot(pixel, vec2(0.06711056, 0.00583715))));
}

// Best-candidate Poisson disk points in the unit disk, set by the renderer (every prefix is well
// spread, so n taps use the first n).
uniform vec2 uPoissonDisk[SG_MAX_SAMPLES];

// A hash of the pixel and an index to [0, 1) (Wang-style integer mixing).
float hashToUnit(uvec2 pixel, uint i) {
    uint h = pixel.x * 1973u + pixel.y * 9277u + i * 26699u;
    h = (h ^ 61u) ^ (h >> 16);
    h *= 9u;
    h ^= h >> 4;
    h *= 0x27d4eb2du;
    h ^= h >> 15;
    return float(h) * (1.0 / 4294967296.0);
}

// Sample i of n of the unit disk with the light's kernel, rotated by `rotation`.
vec2 diskSample(int kernel, int i, int n, float rotation) {
    if (kernel == SG_KERNEL_POISSON) {
        vec2 p = uPoissonDisk[i];
        float c = cos(rotation), s = sin(rotation);
        return vec2(c * p.x - s * p.y, s * p.x + c * p.y);
    }
    if (kernel == SG_KERNEL_UNIFORM) {
        uvec2 pixel = uvec2(gl_FragCoord.xy);
        float radius = sqrt(hashToUnit(pixel, uint(2 * i)));
        float angle = 6.28318531 * hashToUnit(pixel, uint(2 * i + 1));
        return radius * vec2(cos(angle), sin(angle));
    }
    // Golden-angle spiral with uniform area density.
    float radius = sqrt((float(i) + 0.5) / float(n));
    float angle = float(i) * kGoldenAngle + rotation;
    return radius * vec2(cos(angle), sin(angle));
}

float hardVisibility(int slot, GpuLight L, Receiver r) {
    return compareTap(slot, L, r, lateralTap(L, r, vec2(0.0)));
}

// Percentage-closer filtering over a disk of `radius` metres (lateral, at the receiver).
float pcfVisibility(int slot, GpuLight L, Receiver r, float radius, int samples) {
    if (radius <= 0.0 || samples <= 1) return hardVisibility(slot, L, r);
    float rotation = 6.28318531 * interleavedGradientNoise(gl_FragCoord.xy);
    float sum = 0.0;
    for (int i = 0; i < samples; ++i) {
        sum += compareTap(slot, L, r, lateralTap(L, r, diskSample(L.kernel, i, samples, rotation) * radius));
    }
    return sum / float(samples);
}

#ifdef SG_TECH_PCSS_ENABLED
// Percentage-closer soft shadows: blocker search, penumbra from similar triangles, PCF.
float pcssVisibility(int slot, GpuLight L, Receiver r) {
    float maxRadius = L.maxFilterTexels * r.texelMetres;
    Tap center = lateralTap(L, r, vec2(0.0));
    float dReceiver = center.depth;
    float size = max(L.emitterSize, 0.0);
    if (size <= 0.0 || maxRadius <= 0.0) return compareTap(slot, L, r, center);

    // Blocker search region, lateral metres at the receiver: the cone from the receiver to
    // the emitter, widest at the nearest depth a blocker can have.
    GpuShadowLayer S = uLayers[L.firstLayer + r.layer];
    float searchRadius;
    if (L.type == SG_LIGHT_DIRECTIONAL) {
        searchRadius = dReceiver * tan(size);
    } else {
        float near = max(S.depthNear, 1e-6);
        searchRadius = size * max(dReceiver - near, 0.0) / near;
    }
    searchRadius = clamp(searchRadius, r.texelMetres, maxRadius);

    float rotation = 6.28318531 * interleavedGradientNoise(gl_FragCoord.xy);
    float blockerSum = 0.0;
    int blockers = 0;
    for (int i = 0; i < L.blockerSamples; ++i) {
        Tap t = lateralTap(L, r, diskSample(L.kernel, i, L.blockerSamples, rotation) * searchRadius);
        float stored = texture(uShadowDepth[slot], vec3(t.uv, float(t.layer))).r *
                       (t.layer == r.layer ? r.depthScale : uLayers[L.firstLayer + t.layer].depthScale);
        if (stored < t.depth - r.depthBias) {
            // Blocker depth expressed at the center's lateral position: the tap's own shift
            // along the tangent plane is removed so a sloped receiver does not bias it.
            blockerSum += stored + (dReceiver - t.depth);
            ++blockers;
        }
    }
    if (blockers == 0) {
        gDebugBlockerDepth = 0.0;
        gDebugPenumbra = 0.0;
        return 1.0;
    }
    float dBlocker = clamp(blockerSum / float(blockers), 0.0, dReceiver);
    // Penumbra half-width at the receiver (m), by similar triangles.
    float penumbra;
    if (L.type == SG_LIGHT_DIRECTIONAL) {
        penumbra = (dReceiver - dBlocker) * tan(size);
    } else {
        penumbra = (dReceiver - dBlocker) * size / max(dBlocker, 1e-6);
    }
    penumbra = min(penumbra, maxRadius);
    gDebugBlockerDepth = dBlocker;
    gDebugPenumbra = penumbra;
    return pcfVisibility(slot, L, r, penumbra, L.pcfSamples);
}
#endif

#ifdef SG_TECH_PCSS_TEXTBOOK_ENABLED
// The seeds' PCSS, kept as the baseline every speed-up is measured against: a fixed-count
// Poisson blocker search and PCF around the receiver's own shadow-map UV (no receiver-plane
// taps, no per-tap layer choice, no early-outs), with the same physical search region,
// penumbra formula, bias and clamp as pcssVisibility.
float pcssTextbookVisibility(int slot, GpuLight L, Receiver r) {
    Tap center = lateralTap(L, r, vec2(0.0));
    GpuShadowLayer S = uLayers[L.firstLayer + center.layer];
    vec3 ls = (S.lightFromWorld * vec4(r.csPosition, 1.0)).xyz;
    float uvPerMetre = 0.5 * S.clipFromLight[0][0] / (S.orthographic != 0 ? 1.0 : max(-ls.z, 1e-6));
    float dReceiver = center.depth;
    float size = max(L.emitterSize, 0.0);
    float maxRadius = L.maxFilterTexels * r.texelMetres;
    float searchRadius = L.type == SG_LIGHT_DIRECTIONAL
                             ? dReceiver * tan(size)
                             : size * max(dReceiver - S.depthNear, 0.0) / max(S.depthNear, 1e-6);
    searchRadius = clamp(searchRadius, r.texelMetres, maxRadius);
    float rotation = 6.28318531 * interleavedGradientNoise(gl_FragCoord.xy);

    float blockerSum = 0.0;
    int blockers = 0;
    for (int i = 0; i < L.blockerSamples; ++i) {
        vec2 uv = center.uv + diskSample(SG_KERNEL_POISSON, i, L.blockerSamples, rotation) * searchRadius * uvPerMetre;
        float stored = texture(uShadowDepth[slot], vec3(uv, float(center.layer))).r * S.depthScale;
        if (stored < dReceiver - r.depthBias) {
            blockerSum += stored;
            ++blockers;
        }
    }
    float dBlocker = blockers > 0 ? blockerSum / float(blockers) : dReceiver;
    float penumbra = L.type == SG_LIGHT_DIRECTIONAL ? (dReceiver - dBlocker) * tan(size)
                                                    : (dReceiver - dBlocker) * size / max(dBlocker, 1e-6);
    penumbra = clamp(penumbra, 0.0, maxRadius);
    gDebugBlockerDepth = dBlocker;
    gDebugPenumbra = penumbra;
    float reference = min((dReceiver - r.depthBias) / S.depthScale, 1.0);
    float sum = 0.0;
    for (int i = 0; i < L.pcfSamples; ++i) {
        vec2 uv = center.uv + diskSample(SG_KERNEL_POISSON, i, L.pcfSamples, rotation) * penumbra * uvPerMetre;
        sum += texture(uShadowCompare[slot], vec4(uv, float(center.layer), reference));
    }
    return sum / float(L.pcfSamples);
}
#endif

float techniqueVisibility(int slot, GpuLight L, Receiver r) {
    float v = 1.0;
#ifdef SG_TECH_HARD_ENABLED
    if (L.technique == SG_TECH_HARD) v = hardVisibility(slot, L, r);
#endif
#ifdef SG_TECH_PCF_ENABLED
    if (L.technique == SG_TECH_PCF) {
        float radius = min(L.pcfRadius, L.maxFilterTexels * r.texelMetres);
        v = pcfVisibility(slot, L, r, radius, L.pcfSamples);
    }
#endif
#ifdef SG_TECH_PCSS_ENABLED
    if (L.technique == SG_TECH_PCSS) v = pcssVisibility(slot, L, r);
#endif
#ifdef SG_TECH_PCSS_TEXTBOOK_ENABLED
    if (L.technique == SG_TECH_PCSS_TEXTBOOK) v = pcssTextbookVisibility(slot, L, r);
#endif
    return v;
}

// Visibility in [0, 1] of light `L` (bound to pass slot `slot`) at a receiver point. Near the
// far end of a cascade the next cascade is blended in over the last `cascadeBlend` fraction
// of its range, so cascade borders do not show as seams.
float shadowVisibility(int slot, GpuLight L, vec3 csPosition, vec3 wsNormal, float viewDistance) {
    if (L.technique == SG_TECH_NONE) return 1.0;
    Receiver r = makeReceiver(L, csPosition, wsNormal, viewDistance, -1);
    gDebugCascade = r.layer;
    float v = techniqueVisibility(slot, L, r);
    if (L.type == SG_LIGHT_DIRECTIONAL && r.layer + 1 < L.layerCount && L.cascadeBlend > 0.0) {
        float end = uLayers[L.firstLayer + r.layer].splitFar;
        float begin = r.layer > 0 ? uLayers[L.firstLayer + r.layer - 1].splitFar : 0.0;
        float band = L.cascadeBlend * (end - begin);
        float w = clamp((viewDistance - (end - band)) / max(band, 1e-6), 0.0, 1.0);
        if (w > 0.0) {
            Receiver next = makeReceiver(L, csPosition, wsNormal, viewDistance, r.layer + 1);
            v = mix(v, techniqueVisibility(slot, L, next), w);
        }
    }
    return clamp(v, 0.0, 1.0);
}
