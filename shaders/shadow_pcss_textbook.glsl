// The seeds' PCSS, the benchmarks' baseline: compiled only into builds with
// SHADOW_BASELINE_TECHNIQUES (the benchmarks'), never offered to a game's shader.
#ifndef SG_SHADOW_PCSS_TEXTBOOK
#define SG_SHADOW_PCSS_TEXTBOOK
#include "shadow_kernels.glsl"
#include "shadow_taps.glsl"
#include "shadow_debug.glsl"
#include "shadow_penumbra.glsl"

// The textbook PCSS compares its whole filter against one reference depth in the map's UV, so it
// keeps the classic remedy: a one-texel normal offset and the whole slope bias.
sg_ReceiverPolicy sg_pcssTextbookPolicy() { return sg_ReceiverPolicy(1.0, 1.0, 0.0); }

// The seeds' PCSS, kept as the baseline every speed-up is measured against: a fixed-count
// Poisson blocker search and PCF around the receiver's own shadow-map UV (no receiver-plane
// taps, no per-tap layer choice, no early-outs), with the same physical search region,
// penumbra formula, bias and clamp as sg_pcssVisibility.
float sg_pcssTextbookVisibility(int slot, sg_GpuLight L, sg_Receiver r) {
    sg_Tap center = sg_receiverTap(r);
    sg_GpuShadowLayer S = sg_layers[L.firstLayer + center.layer];
    vec3 ls = (S.lightFromCs * vec4(r.csPosition, 1.0)).xyz;
    float uvPerMetre = 0.5 * S.clipFromLight[0][0] / (L.type == SG_LIGHT_DIRECTIONAL ? 1.0 : max(-ls.z, 1e-6));
    float dReceiver = center.depth;
    float size = max(L.emitterSize, 0.0);
    float maxRadius = L.maxFilterTexels * r.texelMetres;
    float searchRadius = clamp(sg_blockerSearchRadius(L, r, dReceiver, size), r.texelMetres, maxRadius);
    sg_DiskWalk disk = sg_beginDisk(sg_pixelRotation(), 0);

    float blockerSum = 0.0;
    int blockers = 0;
    SG_ISOLATED
    for (int i = 0; i < L.blockerSamples; ++i) {
        vec2 uv = center.uv + sg_nextDiskSample(SG_KERNEL_POISSON, disk, i) * searchRadius * uvPerMetre;
        float stored = texture(sg_shadowDepth[slot], vec3(uv, float(center.layer))).r * S.depthScale;
        if (stored < dReceiver - r.depthBias) {
            blockerSum += stored;
            ++blockers;
        }
    }
    float dBlocker = blockers > 0 ? blockerSum / float(blockers) : dReceiver;
    float penumbra = clamp(sg_penumbraRadius(L, dReceiver, dBlocker, size), 0.0, maxRadius);
    SG_DEBUG_STORE(sg_debugBlockerDepth, dBlocker);
    SG_DEBUG_STORE(sg_debugPenumbra, penumbra);
    float reference = min((dReceiver - r.depthBias) / S.depthScale, 1.0);
    float sum = 0.0;
    SG_ISOLATED
    for (int i = 0; i < L.pcfSamples; ++i) {
        vec2 uv = center.uv + sg_nextDiskSample(SG_KERNEL_POISSON, disk, i) * penumbra * uvPerMetre;
        sum += texture(sg_shadowCompare[slot], vec4(uv, float(center.layer), reference));
    }
    return sum / float(L.pcfSamples);
}
#endif
