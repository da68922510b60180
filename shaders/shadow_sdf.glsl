// Distance-field soft shadows (technique sdf): from the receiver a ray is marched toward the
// light through the signed distance fields of the casters it can meet, each step as long as the
// nearest field allows (sphere tracing). At distance t along the ray the emitter subtends a cone
// of radius t * tan(e) (e: the emitter's angular radius seen from the receiver: `emitterSize` /
// distance for a spot's disk or a point's sphere, `emitterSize` itself for a sun); a caster
// whose surface passes at clearance d from the ray covers the part of the emitter's disk beyond
// a straight edge at u = d / (t tan e) of its radius. The smallest u along the ray gives the
// visibility, the disk's area beyond that edge (1 at u >= 1, 1/2 at the geometric edge u = 0, 0
// at u <= -1): penumbrae in the same physical units as PCSS, straddling the hard edge as the
// ray-traced truth's do. The ray goes on through a closed caster (its field is negative inside,
// steps are |d|), so u goes below 0 in the umbra; an open caster is a sheet (its field is
// unsigned), which a ray that comes within the shortest step of it counts as crossed (u = -1).
//
// The seeds' estimate, min k d / t, bands and leaks where the ray passes a corner or a thin
// caster between two samples; this follows the improved estimate (Aaltonen, GDC 2018): from
// the last two distances the closest approach between the samples, y = d^2 / (2 d_prev) along
// the ray and sqrt(d^2 - y^2) across it.
//
// Costs follow what the ray can meet: before marching, the light's clusters of field casters and
// then the casters of the clusters the ray meets are tested by bounding sphere against the ray
// segment, and only the SG_SDF_MAX_NEAR nearest casters it meets are sampled per step; the march ends where the ray leaves the last of them, at
// the light, after `sdfSteps` steps, or in full umbra. Casters without a field (a game's own
// draws, non-uniform scales) stay in the light's shadow map: one hard tap, multiplied in.
//
// Instance records (SG_SDF_INSTANCE_TEXELS vec4 of the buffer texture per field caster, written
// by engine/src/shadow/distance_field_atlas.cpp):
//   0-2  rows of the camera-relative-world -> mesh-local matrix
//   3    xyz: the first voxel centre (local), w: the voxel's edge (local units)
//   4    xyz: the last voxel centre (local), w: metres per local unit (the uniform scale)
//   5    xyz: the atlas texel of the brick's first voxel, w: 1 for an unsigned (open) field
//   6    xyz: bounding sphere centre (camera-relative, m), w: its radius (m); < 0 for none
//   7, 8 xyz: the mesh's own bounds (local), min and max
// After every instance, each light's clusters of up to SG_SDF_CLUSTER instances (consecutive in
// the Morton order of their centres), at the same stride:
//   0    xyz: the sphere around the cluster's spheres (camera-relative, m), w: radius; < 0 none
//   1    x: the cluster's first instance, y: its instance count
#ifndef SG_SHADOW_SDF
#define SG_SHADOW_SDF
#include "shadow_taps.glsl"
#include "shadow_debug.glsl"

layout(binding = SG_UNIT_SDF_ATLAS) uniform sampler3D sg_sdfAtlas;
layout(binding = SG_UNIT_SDF_INSTANCES) uniform samplerBuffer sg_sdfInstances;

sg_ReceiverPolicy sg_sdfPolicy() { return sg_planePolicy(); }

vec4 sg_sdfRecord(int instance, int k) { return texelFetch(sg_sdfInstances, instance * SG_SDF_INSTANCE_TEXELS + k); }

// Distance (m) from camera-relative `p` to field caster `instance`: trilinear between the voxel
// centres, and beyond them the larger of the distance to the mesh's bounds and the nearest
// centre's value less the way to it (both lower bounds: the march never oversteps into the mesh).
float sg_sdfDistance(int instance, vec3 p) {
    vec4 p4 = vec4(p, 1.0);
    vec3 q = vec3(dot(sg_sdfRecord(instance, 0), p4), dot(sg_sdfRecord(instance, 1), p4),
                  dot(sg_sdfRecord(instance, 2), p4));
    vec4 first = sg_sdfRecord(instance, 3);
    vec4 last = sg_sdfRecord(instance, 4);
    vec4 brick = sg_sdfRecord(instance, 5);
    vec3 c = clamp(q, first.xyz, last.xyz);
    vec3 texel = brick.xyz + (c - first.xyz) / first.w + 0.5;
    float d = texture(sg_sdfAtlas, texel / vec3(textureSize(sg_sdfAtlas, 0))).r;
    float away = length(q - c);
    if (away > 0.0) {
        vec3 outside = max(max(sg_sdfRecord(instance, 7).xyz - q, q - sg_sdfRecord(instance, 8).xyz), 0.0);
        d = max(length(outside), d - away);
    }
    return d * last.w;
}

// Where the segment origin + t dir, t in [0, tEnd], meets `sphere` (xyz centre, w radius): the
// (entry, exit) t, or exit -1 when it does not (or the sphere is none, w < 0).
vec2 sg_sdfRayEnters(vec3 origin, vec3 dir, float tEnd, vec4 sphere) {
    if (sphere.w < 0.0) return vec2(0.0, -1.0);
    vec3 oc = origin - sphere.xyz;
    float b = dot(oc, dir);
    float h = b * b - (dot(oc, oc) - sphere.w * sphere.w);
    if (h < 0.0) return vec2(0.0, -1.0);
    h = sqrt(h);
    float t0 = -b - h, t1 = -b + h;
    return t1 < 0.0 || t0 > tEnd ? vec2(0.0, -1.0) : vec2(t0, t1);
}

// The part of the emitter's disk beyond a straight edge at signed distance u of its radius.
float sg_sdfVisibleFraction(float u) {
    u = clamp(u, -1.0, 1.0);
    return 1.0 - (acos(u) - u * sqrt(1.0 - u * u)) / 3.14159265;
}

// A ray crossing a sheet (an open caster, whose unsigned field has no inside) at `p`: how far
// inside the sheet's edge it crosses, over the cone's radius `radius` there, as a negative u.
// The sheet's plane comes from the field's gradient a little before the crossing; of eight
// points at `radius` around `p` in that plane, the one farthest from the sheet puts the edge at
// radius - d from `p` (beyond its edge, a sheet's field is the distance to the edge); a crossing
// deeper than the cone's radius is -1 (umbra).
float sg_sdfSheetClearance(int instance, vec3 p, vec3 dir, float radius) {
    float h = 0.25 * radius + 1e-4;
    vec3 before = p - dir * (2.0 * h);
    vec3 n = vec3(sg_sdfDistance(instance, before + vec3(h, 0, 0)) - sg_sdfDistance(instance, before - vec3(h, 0, 0)),
                  sg_sdfDistance(instance, before + vec3(0, h, 0)) - sg_sdfDistance(instance, before - vec3(0, h, 0)),
                  sg_sdfDistance(instance, before + vec3(0, 0, h)) - sg_sdfDistance(instance, before - vec3(0, 0, h)));
    vec3 t1, t2;
    sg_perpendicularBasis(sg_safeNormalize(n, dir), t1, t2);
    float farthest = 0.0;
    for (int k = 0; k < 8; ++k) {
        float angle = 0.78539816 * float(k);
        farthest = max(farthest, sg_sdfDistance(instance, p + radius * (cos(angle) * t1 + sin(angle) * t2)));
    }
    return -clamp((radius - farthest) / max(radius, 1e-6), 0.0, 1.0);
}

float sg_sdfMarch(sg_GpuLight L, sg_Receiver r) {
    if (L.sdfCount <= 0) return 1.0;
    // Start off the surface, on the side that faces the light.
    vec3 n = dot(r.csNormal, r.toLight) < 0.0 ? -r.csNormal : r.csNormal;
    vec3 origin = r.csPosition + n * L.sdfStartOffset;
    bool sun = L.type == SG_LIGHT_DIRECTIONAL;
    vec3 dir = sun ? -L.wsDirection : sg_safeNormalize(L.csPosition - origin, r.toLight);
    float tEnd = sun ? 1e30 : length(L.csPosition - origin);
    // A point-sized emitter (tan e = 0) is a cone of 1e-6: the hard shadow, without 0/0.
    float tanE = max(sun ? tan(max(L.emitterSize, 0.0)) : max(L.emitterSize, 0.0) / max(tEnd, 1e-6), 1e-6);

    // The field casters the ray segment meets, by bounding sphere, cluster by cluster: the
    // nearest SG_SDF_MAX_NEAR.
    int near[SG_SDF_MAX_NEAR];
    float enter[SG_SDF_MAX_NEAR];
    int count = 0;
    float tStop = 0.0;
    int clusters = (L.sdfCount + SG_SDF_CLUSTER - 1) / SG_SDF_CLUSTER;
    int cluster = -1;
    int i = 0, end = 0;
    while (true) {
        if (i >= end) {  // the next cluster the ray meets, or done
            for (++cluster; cluster < clusters; ++cluster) {
                if (sg_sdfRayEnters(origin, dir, tEnd, sg_sdfRecord(L.sdfClusterFirst + cluster, 0)).y >= 0.0) break;
            }
            if (cluster >= clusters) break;
            vec4 range = sg_sdfRecord(L.sdfClusterFirst + cluster, 1);
            i = int(range.x);
            end = i + int(range.y);
        }
        int instance = i++;
        vec2 span = sg_sdfRayEnters(origin, dir, tEnd, sg_sdfRecord(instance, 6));
        if (span.y < 0.0) continue;
        float t0 = span.x, t1 = span.y;
        tStop = max(tStop, t1);
        int slotK = count;
        if (count < SG_SDF_MAX_NEAR) {
            ++count;
        } else {  // full: replace the farthest entry if this one starts nearer
            slotK = 0;
            for (int k = 1; k < SG_SDF_MAX_NEAR; ++k) slotK = enter[k] > enter[slotK] ? k : slotK;
            if (enter[slotK] <= t0) continue;
        }
        near[slotK] = instance;
        enter[slotK] = t0;
    }
    tStop = min(tStop, tEnd);

    float t = L.sdfStartOffset;
    float lowest = 1.0;  // smallest u seen
    float lastD = 1e30;
    int steps = 0;
    for (; steps < L.sdfSteps && t < tStop && count > 0; ++steps) {
        vec3 p = origin + dir * t;
        float d = 1e30;
        int nearest = 0;
        for (int k = 0; k < count; ++k) {
            float dk = sg_sdfDistance(near[k], p);
            if (dk < d) {
                d = dk;
                nearest = k;
            }
        }
        bool sheet = sg_sdfRecord(near[nearest], 5).w > 0.5;
        float u;
        if (sheet && d < L.sdfMinStep) {
            u = sg_sdfSheetClearance(near[nearest], p, dir, t * tanE);
        } else if (d > 0.0 && lastD < 1e30) {
            float y = min(d * d / (2.0 * lastD), d);
            u = sqrt(max(d * d - y * y, 0.0)) / (max(t - y, 1e-6) * tanE);
        } else {
            u = d / (t * tanE);
        }
        lowest = min(lowest, u);
        if (lowest <= -1.0) break;
        lastD = max(d, 1e-6);
        t += max(abs(d), L.sdfMinStep);
    }
    SG_DEBUG_STORE(sg_debugMarchSteps, float(steps));
    SG_DEBUG_STORE(sg_debugClosest, clamp(lowest, -1.0, 1.0));
    return sg_sdfVisibleFraction(lowest);
}

float sg_sdfVisibility(int slot, sg_GpuLight L, sg_Receiver r) {
    float mapped = sg_compareTap(slot, L, r, sg_lateralTap(L, r, vec2(0.0)));
    return mapped <= 0.0 ? 0.0 : mapped * sg_sdfMarch(L, r);
}

#endif
