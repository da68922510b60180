// The PCSS filter, shared by the pcss technique and by sdf's casters without a field: blocker
// search, penumbra width from similar triangles in the emitter's physical size
// (docs/output_contract.md, conventions), then PCF over that width. The min/max pyramid answers
// for the whole search region first: where it holds no blocker or only blockers, neither the
// search nor the filter takes a tap.
//
// Reference: R. Fernando, "Percentage-Closer Soft Shadows", SIGGRAPH 2005 sketch.
#ifndef SG_SHADOW_PCSS_FILTER
#define SG_SHADOW_PCSS_FILTER
#include "shadow_filter.glsl"
#include "shadow_region.glsl"
#include "shadow_debug.glsl"
#include "shadow_penumbra.glsl"

float sg_pcssFilter(int slot, sg_GpuLight L, sg_Receiver receiver) {
    sg_Receiver r = sg_emitterShaped(L, receiver);
    float maxRadius = L.maxFilterTexels * r.texelMetres;
    sg_Tap center = sg_receiverTap(r);
    float dReceiver = center.depth;
    float size = max(L.emitterSize, 0.0);
    bool pointEmitter = size <= 0.0 || maxRadius <= 0.0;  // a hard shadow: one tap at the receiver
    float searchRadius = clamp(sg_blockerSearchRadius(L, r, dReceiver, size), r.texelMetres, maxRadius);
    float known = pointEmitter ? -1.0 : sg_regionVisibility(slot, L, r, center, searchRadius);

    // The search gathers 2x2 depth texels at blockerSamples / 2 points of the disk (textureGather,
    // GL 4.0): twice the depths of single taps for half the fetches, at the same error (fewer
    // points cluster; docs/tuning.md).
    int gathers = (L.blockerSamples + 1) / 2;
    vec2 rotation = sg_pixelRotation();
    int searchGathers = known >= 0.0 || pointEmitter ? 0 : gathers;
    // Twice at most: the second search, over the cone to the blockers the first found, where
    // that is under half the first region (sg_refinesSearch, as VSSM's and MSM-soft's), with half
    // the gathers (a region that narrow holds a few texels: all the gathers measured the same).
    float radius = searchRadius;
    float penumbra = 0.0;
    float dBlocker = 0.0;
    bool found = false;
#ifdef SG_STAGE_FEATURES
    bool mixed = false;  // the first search found blockers and texels that do not
    float nearestBlocker = 3.0e38;  // lateral m from the receiver to the nearest tap that found one
#endif
    SG_ISOLATED
    for (int pass = 0; pass < 2 && searchGathers > 0; ++pass) {
        sg_DiskWalk disk = sg_beginDisk(rotation, searchGathers);  // the whole disk at this count
        float blockerSum = 0.0;
        float blockers = 0.0;
        SG_ISOLATED
        for (int i = 0; i < searchGathers; ++i) {
            vec2 offset = sg_nextDiskSample(L.kernel, disk, i) * radius;
            sg_Tap t = sg_lateralTap(L, r, offset);
            float scale = t.layer == r.layer ? r.depthScale : sg_layers[L.firstLayer + t.layer].depthScale;
            vec2 f, quadUv;
            vec4 references = sg_quadReferences(L, r, t, f, quadUv) * scale;
            vec4 stored = textureGather(sg_shadowDepth[slot], vec3(quadUv, float(t.layer))) * scale;
            vec4 blocks = vec4(lessThan(stored, references));
            // Blocker depth carried to the receiver's own ray, so that neither a sloped receiver
            // nor a perspective light's rays bias it. An orthographic light's depth is axial: the
            // tap's shift along the tangent plane is removed. A perspective light's depth is a
            // distance, which grows off the axis as 1/cos for the receiver and the blocker
            // alike: the ratio of the two along the tap's ray is what similar triangles keep, so
            // the depth is scaled (a shift would move blockers off axis by the receiver's
            // growth, not their own).
            vec4 carried =
                r.orthographic ? stored + (dReceiver - t.depth) : stored * (dReceiver / max(t.depth, 1e-30));
            blockerSum += dot(blocks, carried);
            blockers += dot(blocks, vec4(1.0));
#ifdef SG_STAGE_FEATURES
            if (pass == 0 && any(greaterThan(blocks, vec4(0.0)))) nearestBlocker = min(nearestBlocker, length(offset));
#endif
        }
        if (blockers <= 0.0) break;  // none (in the narrower cone: the first estimate stands)
#ifdef SG_STAGE_FEATURES
        mixed = mixed || (!found && blockers < 4.0 * float(searchGathers));
#endif
        float d = clamp(blockerSum / blockers, 0.0, dReceiver);
        // Penumbra half-width at the receiver (m), by similar triangles.
        float p = min(sg_penumbraRadius(L, dReceiver, d, size), maxRadius);
        if (!found || p < penumbra) {
            penumbra = p;
            dBlocker = d;
        }
        found = true;
        if (!sg_refinesSearch(penumbra, radius)) break;
        radius = penumbra;
        searchGathers = max(searchGathers / 2, 1);
    }
    int taps = pointEmitter ? 1 : (found ? sg_tapsFor(penumbra / r.texelMetres, L.pcfSamples) : 0);
    float filtered = sg_pcfTaps(slot, L, r, penumbra, taps, false);
    SG_DEBUG_STORE(sg_debugBlockerDepth, found ? dBlocker : 0.0);
    SG_DEBUG_STORE(sg_debugPenumbra, penumbra);
#ifdef SG_STAGE_FEATURES
    // Where mixed, the visibility changes over the penumbra near the blockers found: within a
    // block of them (the search region can be far wider). A point emitter's: over a texel.
    SG_STAGE_FEATURE(pointEmitter ? r.texelMetres : (mixed && nearestBlocker < sg_stageBlock + penumbra ? penumbra : 3.0e38));
#endif
    if (known >= 0.0) return known;
    return taps > 0 ? filtered : 1.0;
}

#endif
