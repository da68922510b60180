// Depth comparisons of a tap: the 2x2 texels around it, each compared with the receiver plane's
// depth at its own centre, less the bias (shadow_receiver.glsl explains the frame of reference).
#ifndef SG_SHADOW_TAPS
#define SG_SHADOW_TAPS
#include "shadow_receiver.glsl"

// The 2x2 texels around a tap, each compared with the receiver plane's depth at its own centre
// (1 = lit), in textureGather's order, and the tap's bilinear weights in the same order.
struct sg_TexelQuad {
    vec4 lit;
    vec2 f;  // the tap's position inside the quad
};

// The 2x2 texels around map position `st` (texels, less half a texel: st = uv * mapSize - 0.5) of
// a map `size` texels wide: the uv of the corner they share, where a gather reads exactly these
// four whatever the sampler's sub-texel rounding (a quad one texel off is a whole gradient step
// off), and `f`, the position inside the quad.
vec2 sg_quadAt(vec2 st, float size, out vec2 f) {
    vec2 base = floor(st);
    f = st - base;
    return (base + 1.0) / size;
}

// The reference depths (stored units) of the 2x2 texels around tap `t`, in textureGather's
// order ((0,1), (1,1), (1,0), (0,0) from the lower-left texel): the receiver plane's depth at each
// texel's own centre, less the bias. `f` is the tap's position inside the quad.
vec4 sg_quadReferences(sg_GpuLight L, sg_Receiver r, sg_Tap t, out vec2 f, out vec2 quadUv) {
    float depthScale = t.layer == r.layer ? r.depthScale : sg_layers[L.firstLayer + t.layer].depthScale;
    // A tap away from the receiver lies on its tangent plane, which a bumpy or curved surface
    // rises above within a tap's reach: the policy's reach bias (PCF's only) lets it.
    float bias = r.depthBias + r.reachBias * t.reach;
    quadUv = sg_quadAt(t.uv * float(L.mapSize) - 0.5, float(L.mapSize), f);
    vec4 steps = t.refPerTexel.x * vec4(-f.x, 1.0 - f.x, 1.0 - f.x, -f.x) +
                 t.refPerTexel.y * vec4(1.0 - f.y, 1.0 - f.y, -f.y, -f.y);
    vec4 depths;
    if (r.orthographic) {
        depths = t.depth + steps;
    } else {
        // 1/axial at each texel centre, back to a distance from the light; a plane that leaves
        // the light's view within the quad is held at twice the tap's distance.
        float inverseAxial = 1.0 / t.axial;
        // The distance along each texel centre's own ray: the map stores distances from the
        // light, and their ratio to the axial distance, sqrt(1 + tan^2), changes by up to 0.6 %
        // per texel at the edge of a 512^2 cube face (11 mm at 2 m), more than the bias. Taken
        // to first order (the second-order term is ~1e-5 of it per texel).
        float ratio = t.depth / t.axial;
        vec2 ratioPerTexel = t.rayTan * r.texelTan / ratio;
        vec4 ratios = ratio + ratioPerTexel.x * vec4(-f.x, 1.0 - f.x, 1.0 - f.x, -f.x) +
                      ratioPerTexel.y * vec4(1.0 - f.y, 1.0 - f.y, -f.y, -f.y);
        depths = ratios / max(inverseAxial + steps, vec4(0.5 * inverseAxial));
    }
    return (depths - bias) / depthScale;
}

// Bilinear blend of a quad's four values in textureGather's order; exact where all four agree.
float sg_bilinearQuad(vec4 v, vec2 f) {
    float bottom = v.w + (v.z - v.w) * f.x;
    float top = v.x + (v.y - v.x) * f.x;
    return bottom + (top - bottom) * f.y;
}

sg_TexelQuad sg_compareQuad(int slot, sg_GpuLight L, sg_Receiver r, sg_Tap t) {
    vec2 f, quadUv;
    vec4 refs = min(sg_quadReferences(L, r, t, f, quadUv), vec4(1.0));
    vec4 stored = textureGather(sg_shadowDepth[slot], vec3(quadUv, float(t.layer)));
    sg_TexelQuad q;
    q.lit = vec4(lessThanEqual(refs, stored));
    q.f = f;
    return q;
}

// 1 where the tap's point is lit, bilinearly filtered over the 2x2 texels around it.
float sg_compareTap(int slot, sg_GpuLight L, sg_Receiver r, sg_Tap t) {
    sg_TexelQuad q = sg_compareQuad(slot, L, r, t);
    return sg_bilinearQuad(q.lit, q.f);
}

#endif
