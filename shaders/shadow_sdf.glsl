// Distance-field soft shadows (technique sdf): from the receiver a ray is marched toward the
// light through the signed distance fields of the casters it can meet, each step as long as the
// nearest field allows (sphere tracing). At distance t along the ray the emitter subtends a cone
// of radius t * tan(e) (e: the emitter's angular radius seen from the receiver: `emitterSize` /
// distance for a spot's disk or a point's sphere, `emitterSize` itself for a sun); a caster
// whose surface passes at clearance d from the ray covers the part of the emitter's disk beyond
// a straight edge at u = d / (t tan e) of its radius. The smallest u along the ray gives the
// visibility, the disk's area beyond that edge (1 at u >= 1, 1/2 at the geometric edge u = 0, 0
// at u <= -1): penumbrae in the same physical units as PCSS, straddling the hard edge as the
// ray-traced truth's do. A spot's disk, seen off its axis, is taken as the disk of equal area.
//
// Inside a closed caster (its field negative) the field's magnitude is the way to the nearest
// face, not to the silhouette's edge, so there the visible fraction comes from the field across
// the ray around the sample (sg_sdfCrossing); an open caster is a sheet (its field is
// unsigned), and a caster thinner than a voxel may have no inside at all: a ray that comes
// within the shortest step of a sheet, or whose distance falls to a minimum within a voxel of a
// caster whose gradient then turns over, has crossed it, and the visible fraction comes from the
// edges around the crossing in its plane (up to two: a corner). The visibility is the smaller of
// the crossings' and the one of the smallest u outside.
//
// The seeds' estimate, min k d / t, bands and leaks where the ray passes a corner or a thin
// caster between two samples; this follows the improved estimate (Aaltonen, GDC 2018): from
// the last two distances the closest approach between the samples, where the spheres free of
// casters around both meet (y = d^2 / (2 d_prev) back along the ray for a step of d_prev).
//
// Costs follow what the ray can meet: before marching, the light's clusters of field casters and
// then the casters of the clusters the cone meets are tested by bounding sphere against the cone
// around the ray segment (a flat caster the ray leaves behind is dropped), and only the
// SG_SDF_MAX_NEAR nearest casters it meets are sampled per step; the march ends where the ray
// leaves the last of them, at the light, after `sdfSteps` steps, or in full umbra. Casters
// without a field (open or thinner than two voxels of their field, skinned, cut-out, sheared, a
// game's own draws) stay in the light's shadow map, filtered as PCSS and multiplied in.
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
#include "shadow_pcss_filter.glsl"

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

// Where the cone around the segment origin + t dir, t in [0, tEnd], of radius t tanE at t, meets
// `sphere` (xyz centre, w radius): the (entry, exit) t, or exit -1 when it does not (or the
// sphere is none, w < 0). A caster that the ray itself passes by but the cone reaches still
// takes light from the emitter: the sphere grows by the cone's radius at its far side (and a
// hair for rounding), so that the march also samples it.
vec2 sg_sdfConeEnters(vec3 origin, vec3 dir, float tEnd, float tanE, vec4 sphere) {
    if (sphere.w < 0.0) return vec2(0.0, -1.0);
    vec3 oc = origin - sphere.xyz;
    float b = dot(oc, dir);
    float radius = (sphere.w + (max(-b, 0.0) + sphere.w) * tanE) * 1.001;
    float h = b * b - (dot(oc, oc) - radius * radius);
    if (h < 0.0) return vec2(0.0, -1.0);
    h = sqrt(h);
    float t0 = -b - h, t1 = -b + h;
    return t1 < 0.0 || t0 > tEnd ? vec2(0.0, -1.0) : vec2(t0, t1);
}

// Whether caster `instance` is flat (its mesh has no extent along a local axis: a ground, a
// wall, a card) and the cone leaves its plane behind: the ray's origin is on one side and the
// ray heads away from the plane more steeply than the cone's half-angle. Such a caster is never
// met, and a receiver on a ground would otherwise spend its first steps climbing off the
// ground's own field (a step is the distance to it, growing by the sine of the light's
// elevation per step): at 15 degrees, some 30 of the march's steps.
bool sg_sdfFlatAndBehind(int instance, vec3 origin, vec3 dir, float tanE) {
    vec3 lo = sg_sdfRecord(instance, 7).xyz;
    vec3 hi = sg_sdfRecord(instance, 8).xyz;
    int axis = lo.x == hi.x ? 0 : (lo.y == hi.y ? 1 : (lo.z == hi.z ? 2 : -1));
    if (axis < 0) return false;
    vec4 row = sg_sdfRecord(instance, axis);  // the local coordinate along `axis`, as a plane
    float above = dot(row, vec4(origin, 1.0)) - lo[axis];
    float away = dot(row.xyz, dir);
    return above * away > 0.0 && abs(away) > tanE * length(row.xyz);
}

// The part of the emitter's disk beyond a straight edge at signed distance u of its radius.
float sg_sdfVisibleFraction(float u) {
    u = clamp(u, -1.0, 1.0);
    return 1.0 - (acos(u) - u * sqrt(1.0 - u * u)) / 3.14159265;
}

// The emitter's visible fraction past the caster's edges around `p`, in the plane through `p`
// square to `axis`, the cone's radius there `radius`. Of eight points at `radius` around `p` in
// that plane, the one farthest from the caster (field value f) puts an edge at radius - f from
// `p` on the caster's side (u < 0), or f - radius beyond it (u > 0): exact for a straight edge,
// beyond which the field is the distance to it; all eight on the caster is umbra. Where `p` is
// on the caster's side, the farther of the two points square to that direction finds a second
// edge (a corner of the caster: the cone's disk passes the first edge and the second), and the
// two cover the emitter as two independent half-planes, 1 - (1 - V1)(1 - V2) visible (exact at
// a right-angled corner through `p`, V1 where there is no second edge: f 0 there). One straight
// edge per ray took a plate's corner for a whole edge and darkened the corners of penumbrae as
// wide as the plate.
float sg_sdfEdgesAround(int instance, vec3 p, vec3 axis, float radius) {
    // (No array of the eight: a software rasteriser spills an indexed array to memory, which
    // doubled the whole march's time; the two square to the best are sampled again.)
    vec3 t1, t2;
    sg_perpendicularBasis(axis, t1, t2);
    float farthest = -1e30;
    vec3 towards = t1;
    for (int k = 0; k < 8; ++k) {
        float angle = 0.78539816 * float(k);
        vec3 w = cos(angle) * t1 + sin(angle) * t2;
        float f = sg_sdfDistance(instance, p + radius * w);
        if (f > farthest) {
            farthest = f;
            towards = w;
        }
    }
    float r = max(radius, 1e-6);
    float v1 = sg_sdfVisibleFraction((farthest - radius) / r);
    if (farthest >= radius || v1 <= 0.0) return v1;
    vec3 side = cross(axis, towards) * radius;
    float second = -1e30;
    for (int k = 0; k < 2 + sg_runtimeZero(); ++k) {
        second = max(second, sg_sdfDistance(instance, p + side));
        side = -side;
    }
    float v2 = sg_sdfVisibleFraction((second - radius) / r);
    return 1.0 - (1.0 - v1) * (1.0 - v2);
}

// Edge of one voxel of caster `instance`'s field, in metres.
float sg_sdfVoxelMetres(int instance) { return sg_sdfRecord(instance, 3).w * sg_sdfRecord(instance, 4).w; }

// The field's gradient (unnormalised) at `p`, by central differences `h` apart.
// (Loops kept loops: every inlined call of sg_sdfDistance is code a game's shader compiles once
// per visibility call.)
vec3 sg_sdfGradient(int instance, vec3 p, float h) {
    vec3 g = vec3(0.0);
    for (int k = 0; k < 6 + sg_runtimeZero(); ++k) {
        vec3 e = vec3(k / 2 == 0, k / 2 == 1, k / 2 == 2) * ((k & 1) == 0 ? h : -h);
        g += sign(e) * sg_sdfDistance(instance, p + e);
    }
    return g;
}

// Kinds of a crossing of the ray through a caster (sg_sdfCrossing).
const int SG_SDF_SHEET = 0;   // within the shortest step of a sheet (an open caster, an unsigned field)
const int SG_SDF_INSIDE = 1;  // inside a closed caster (its field negative)
const int SG_SDF_THIN = 2;    // the distance at a minimum within a voxel of a caster

// The emitter's visible fraction where the ray crosses caster `instance` at `p` (the cone's
// radius there `radius`), 1 when it turns out not to cross:
//  - a sheet: the edges around `p` in the sheet's plane, whose normal is the field's gradient a
//    little before the crossing, where the gradient turns over as below (a ray that only runs
//    beside the sheet within the shortest step does not cross it);
//  - inside a closed caster: the field's magnitude there is the way to the nearest face, not to
//    the silhouette's edge (a plate 2 cm thick would put every ray through it within 1 cm of
//    lit, and the umbra side of every penumbra would be too light), so the edges around `p`
//    across the ray; `p` deeper than the radius is umbra without a sample;
//  - a minimum of the distance within a voxel (`voxel`, m): a sheet, or a caster thinner than a
//    voxel (a 1 mm plate in a field of 1 cm voxels, whose interpolated field need not go
//    negative), crossed at a slant between two samples, or a surface passed close by. A
//    crossing turns the field's gradient over (it points back along the ray before and ahead
//    after, from opposite sides of one plane); then as for a sheet.
float sg_sdfCrossing(int kind, int instance, vec3 p, vec3 dir, float d, float radius, float voxel) {
    if (kind == SG_SDF_INSIDE && -d >= radius) return 0.0;
    vec3 axis = dir;
    if (kind != SG_SDF_INSIDE) {
        float h = kind == SG_SDF_SHEET ? 0.25 * radius + 1e-4 : max(0.5 * voxel, 1e-4);
        vec3 before = vec3(0.0);
        vec3 after = vec3(0.0);
        for (int j = 0; j < 2 + sg_runtimeZero(); ++j) {
            vec3 g = sg_sdfGradient(instance, p + dir * (j == 0 ? -2.0 * h : 2.0 * h), h);
            if (j == 0) before = g;
            else after = g;
        }
        if (dot(before, after) >= 0.0) return 1.0;
        axis = sg_safeNormalize(before, dir);
    }
    return sg_sdfEdgesAround(instance, p, axis, radius);
}

#ifdef SG_STAGE_FEATURES
// The stage's samples: a caster the cone (radius `cone`) missed by under a block may shadow a
// neighbour, over a penumbra as wide as the cone (the narrowest is the feature).
void sg_sdfNearMiss(inout float nearMiss, float cone, float distance) {
    if (distance - cone < sg_stageBlock) nearMiss = min(nearMiss, cone);
}
#endif

float sg_sdfMarch(sg_GpuLight L, sg_Receiver r) {
    if (L.sdfCount <= 0) return 1.0;
    // Start off the surface, on the side that faces the light.
    vec3 n = dot(r.csNormal, r.toLight) < 0.0 ? -r.csNormal : r.csNormal;
    vec3 origin = r.csPosition + n * L.sdfStartOffset;
    bool sun = L.type == SG_LIGHT_DIRECTIONAL;
    vec3 dir = sun ? -L.wsDirection : sg_safeNormalize(L.csPosition - origin, r.toLight);
    float tEnd = sun ? 1e30 : length(L.csPosition - origin);
    // A point-sized emitter (tan e = 0) is a cone of 1e-6: the hard shadow, without 0/0. A
    // spot's elliptic emitter: the cone takes the disk of the same area.
    float emitter = sg_apparentEmitterSize(L, dir);
    float tanE = max(sun ? tan(emitter) : emitter / max(tEnd, 1e-6), 1e-6);

    // The field casters the cone around the ray segment meets, by bounding sphere, cluster by cluster: the
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
                if (sg_sdfConeEnters(origin, dir, tEnd, tanE, sg_sdfRecord(L.sdfClusterFirst + cluster, 0)).y >= 0.0) break;
            }
            if (cluster >= clusters) break;
            vec4 range = sg_sdfRecord(L.sdfClusterFirst + cluster, 1);
            i = int(range.x);
            end = i + int(range.y);
        }
        int instance = i++;
        vec2 span = sg_sdfConeEnters(origin, dir, tEnd, tanE, sg_sdfRecord(instance, 6));
        if (span.y < 0.0 || sg_sdfFlatAndBehind(instance, origin, dir, tanE)) continue;
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

#ifdef SG_STAGE_FEATURES
    float nearMiss = 3.0e38;
    // Near misses at the start, but of the receiver's own surface (a box at whose foot it lies).
    for (int k = 0; k < count; ++k) {
        if (abs(sg_sdfDistance(near[k], r.csPosition)) > 0.5 * sg_sdfVoxelMetres(near[k]))
            sg_sdfNearMiss(nearMiss, L.sdfStartOffset * tanE, sg_sdfDistance(near[k], origin));
    }
#endif
    float t = L.sdfStartOffset;
    float lowest = 1.0;   // smallest u seen outside the casters (>= 0)
    float crossed = 1.0;  // smallest visible fraction where the ray crossed a caster
    float lastD = -1.0;  // none yet
    float lastLastD = -1.0;
    int lastNear = -1;  // the caster nearest the last sample (outside it), or -1
    float step = 1.0;
    // The march's budget sets how finely it follows a caster's surface: 24 steps a half of the
    // cone's radius, 48 a quarter, 96 an eighth (see the shortest step below).
    float coneShare = 12.0 / float(max(L.sdfSteps, 1));
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
        // The shortest step: sdfMinStep, and nearer a caster (or inside it) than the cone's
        // share (coneStep) that share, up to one voxel of the caster's field. The cone's radius is
        // the scale of what the visibility can tell apart there (u = d / (t tan e)); finer steps
        // beside a surface the ray runs along or through a caster's edge spent the budget short
        // of the casters beyond, which then let light through (builtin:default at 24 steps,
        // RMSE 0.041 -> 0.018). One voxel at most: a closed caster two voxels thick is not
        // stepped over. A sheet is crossed where the ray comes within the shortest step.
        float coneStep = coneShare * t * tanE;
        float shortest = L.sdfMinStep;
        if (d < coneStep) shortest = max(shortest, min(coneStep, sg_sdfVoxelMetres(near[nearest])));
        float u = 1.0;
        int kind = -1;  // a crossing at this step (SG_SDF_*), or none
        int crossing = near[nearest];
        vec3 at = p;
        float tAt = t;
        float voxel = 0.0;
        if (d >= 0.0 && d < shortest && d <= lastD && sg_sdfRecord(near[nearest], 5).w > 0.5) {  // a sheet
            kind = SG_SDF_SHEET;
        } else if (d < 0.0) {
            kind = SG_SDF_INSIDE;
        }
        if (d >= 0.0) {
            u = d / (t * tanE);
            // The closest approach between this sample and the last: where the spheres free of
            // casters around both (radii lastD and d, `step` apart) meet, y back along the ray.
            // With a step of lastD this is the improved estimate's y = d^2 / (2 lastD); a step
            // stretched to sdfMinStep may leave a gap between the spheres (y >= d), across
            // which nothing is known: the sample's own clearance stands.
            float y = (d * d - lastD * lastD + step * step) / (2.0 * step);
            if (d > 0.0 && lastD > 0.0 && y > 0.0 && y < d) u = min(u, sqrt(d * d - y * y) / (max(t - y, 1e-6) * tanE));
        }
        // A thin caster crossed between the last samples: an unsigned field interpolated across a
        // sheet between voxel centres does not fall below about half a voxel, nor a plate
        // thinner than a voxel below zero, so a ray crossing it at a slant steps over it. The
        // distance falling to a minimum within a voxel marks a crossing or a close pass.
        if (kind < 0 && lastNear >= 0 && d > lastD && lastD <= lastLastD) {
            voxel = sg_sdfVoxelMetres(lastNear);
            if (lastD < voxel) {
                kind = SG_SDF_THIN;
                crossing = lastNear;
                tAt = t - step;
                at = origin + dir * tAt;
            }
        }
        if (kind >= 0) {
            float fraction = sg_sdfCrossing(kind, crossing, at, dir, d, tAt * tanE, voxel);
            crossed = min(crossed, fraction);
            // At a sheet the ray crosses, its fraction stands for the clearance (~0 there).
            if (kind == SG_SDF_SHEET && fraction < 1.0) u = 1.0;
        }
        lowest = min(lowest, u);
#ifdef SG_STAGE_FEATURES
        // Near misses: a minimum of the distance at the last sample.
        if (d > lastD && lastD >= 0.0 && lastD <= lastLastD) sg_sdfNearMiss(nearMiss, (t - step) * tanE, lastD);
#endif
        if (crossed <= 0.0) break;
        lastLastD = lastD;
        lastD = d;
        lastNear = d >= 0.0 ? near[nearest] : -1;
        step = max(abs(d), shortest);
        t += step;
    }
    SG_DEBUG_STORE(sg_debugMarchSteps, float(steps));
    float visible = min(sg_sdfVisibleFraction(lowest), crossed);
    // Outside the umbra the visibility may change over that width nearby.
#ifdef SG_STAGE_FEATURES
    SG_STAGE_FEATURE(visible > 0.0 ? nearMiss : 3.0e38);
#endif
    // The debug view's clearance: u outside, and a crossing's fraction mapped onto [-1, 1].
    SG_DEBUG_STORE(sg_debugClosest, min(min(lowest, 1.0), 2.0 * crossed - 1.0));
    return visible;
}

// The march's visibility times that of the casters the light's map holds instead (open and thin
// meshes, skinned and cut-out ones, a game's own draws), filtered as PCSS filters them: the
// product of the two occluders' visible fractions (exact where they cover the emitter
// independently). A light whose map holds no caster skips the map.
float sg_sdfVisibility(int slot, sg_GpuLight L, sg_Receiver r) {
    float mapped = 1.0;
    SG_ISOLATED for (int k = 0; k < L.sdfMapCasters; ++k) mapped = sg_pcssFilter(slot, L, r);
    return mapped <= 0.0 ? 0.0 : mapped * sg_sdfMarch(L, r);
}

#endif
