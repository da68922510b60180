// Sample patterns of the filters: the unit-disk kernels a light chooses (extras.shadow.kernel)
// and the per-pixel rotation that turns their structure into fine noise.
//
// References: J. Jimenez, "Next Generation Post Processing in Call of Duty: Advanced Warfare",
// SIGGRAPH 2014 (interleaved gradient noise); H. Vogel, "A better way to construct the
// sunflower head", 1979 (golden-angle spiral); D. Mitchell, "Spectrally optimal sampling for
// distribution ray tracing", SIGGRAPH 1991 (best-candidate Poisson disk).
#ifndef SG_SHADOW_KERNELS
#define SG_SHADOW_KERNELS

const float sg_kGoldenAngle = 2.39996323;

// Per-pixel rotation of the sample pattern, stable from frame to frame (Jimenez 2014).
float sg_interleavedGradientNoise(vec2 pixel) {
    return fract(52.9829189 * fract(dot(pixel, vec2(0.06711056, 0.00583715))));
}

// Best-candidate Poisson disk points in the unit disk (every prefix is well spread, so n taps use
// the first n), two per vec4: the shadow system fills the block once (ShadowSystem::kernelBuffer).
layout(std140, binding = SG_BINDING_KERNELS) uniform sg_KernelBlock {
    vec4 sg_poissonPairs[SG_MAX_SAMPLES / 2];
};

vec2 sg_poissonPoint(int i) {
    vec4 pair = sg_poissonPairs[i >> 1];
    return (i & 1) == 0 ? pair.xy : pair.zw;
}

// A hash of the pixel and an index to [0, 1) (Wang-style integer mixing).
float sg_hashToUnit(uvec2 pixel, uint i) {
    uint h = pixel.x * 1973u + pixel.y * 9277u + i * 26699u;
    h = (h ^ 61u) ^ (h >> 16);
    h *= 9u;
    h ^= h >> 4;
    h *= 0x27d4eb2du;
    h ^= h >> 15;
    return float(h) * (1.0 / 4294967296.0);
}

// (cos, sin) of `angle`: a rotation of the plane.
vec2 sg_rotationOf(float angle) {
    return vec2(cos(angle), sin(angle));
}

vec2 sg_rotate(vec2 p, vec2 rotation) {
    return vec2(rotation.x * p.x - rotation.y * p.y, rotation.y * p.x + rotation.x * p.y);
}

// The pixel's rotation of the kernels, stable from frame to frame.
vec2 sg_pixelRotation() {
    return sg_rotationOf(6.28318531 * sg_interleavedGradientNoise(gl_FragCoord.xy));
}

// One golden-angle step of the Vogel spiral as a rotation: sg_rotationOf(sg_kGoldenAngle).
const vec2 sg_kGoldenStep = vec2(-0.73736888, 0.67549029);

// A walk over the n samples of a kernel, rotated by the pixel's angle. The spiral's direction
// advances by one rotation per sample, so no sample pays for a sine or a cosine.
struct sg_DiskWalk {
    vec2 rotation;  // the pixel's rotation
    vec2 spiral;    // Vogel: direction of the next sample
    float count;
};

sg_DiskWalk sg_beginDisk(vec2 rotation, int count) {
    return sg_DiskWalk(rotation, rotation, float(count));
}

// Sample i (taken in order 0, 1, ...) of the walk, in the unit disk, with the light's kernel.
vec2 sg_nextDiskSample(int kernel, inout sg_DiskWalk w, int i) {
    if (kernel == SG_KERNEL_POISSON) return sg_rotate(sg_poissonPoint(i), w.rotation);
    if (kernel == SG_KERNEL_UNIFORM) {
        uvec2 pixel = uvec2(gl_FragCoord.xy);
        float radius = sqrt(sg_hashToUnit(pixel, uint(2 * i)));
        return radius * sg_rotationOf(6.28318531 * sg_hashToUnit(pixel, uint(2 * i + 1)));
    }
    // Golden-angle spiral with uniform area density.
    vec2 p = sqrt((float(i) + 0.5) / w.count) * w.spiral;
    w.spiral = sg_rotate(w.spiral, sg_kGoldenStep);
    return p;
}

#endif
