#include "emitters.h"

#include <shadow/math.h>
#include <shadow/scene.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace shadow::reference {
namespace {

constexpr double kMaxRadius = 1e3;         // Light::radius range
constexpr double kMaxAngularRadius = 0.2;  // Light::angularRadius range

/// Kensler's hash-based permutation of [0, length): element `i` of permutation `p`.
std::uint32_t permute(std::uint32_t i, std::uint32_t length, std::uint32_t p) {
    std::uint32_t w = length - 1;
    w |= w >> 1;
    w |= w >> 2;
    w |= w >> 4;
    w |= w >> 8;
    w |= w >> 16;
    do {
        i ^= p;
        i *= 0xe170893du;
        i ^= p >> 16;
        i ^= (i & w) >> 4;
        i ^= p >> 8;
        i *= 0x0929eb3fu;
        i ^= p >> 23;
        i ^= (i & w) >> 1;
        i *= 1u | p >> 27;
        i *= 0x6935fa69u;
        i ^= (i & w) >> 11;
        i *= 0x74dcb303u;
        i ^= (i & w) >> 2;
        i *= 0x9e501cc3u;
        i ^= (i & w) >> 2;
        i *= 0xc860a3dfu;
        i &= w;
        i ^= i >> 5;
    } while (i >= length);
    return (i + p) % length;
}

/// Kensler's hash to a float in [0, 1).
double randomUnit(std::uint32_t i, std::uint32_t p) {
    i ^= p;
    i ^= i >> 17;
    i ^= i >> 10;
    i *= 0xb36534e5u;
    i ^= i >> 12;
    i ^= i >> 21;
    i *= 0x93fc4795u;
    i ^= 0xdf6e307fu;
    i ^= i >> 17;
    i *= 1u | p >> 18;
    return i * (1.0 / 4294967296.0);
}

std::uint64_t splitMix64(std::uint64_t x) {
    x += 0x9e3779b97f4a7c15ull;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
    return x ^ (x >> 31);
}

/// A point of the disk of `radius` centred on `center` with unit normal `normal`.
glm::dvec3 onDisk(const glm::dvec3& center, const glm::dvec3& normal, double radius, const glm::dvec2& disk) {
    if (radius <= 0.0) return center;
    const glm::dvec3 t1 = anyPerpendicular(normal);
    const glm::dvec3 t2 = glm::cross(normal, t1);
    return center + radius * (disk.x * t1 + disk.y * t2);
}

ShadowRayAim aimAtPoint(const glm::dvec3& from, const glm::dvec3& target) {
    const glm::dvec3 d = target - from;
    const double distance = glm::length(d);
    if (!(distance > 0.0)) return {};
    return {d / distance, distance};
}

/// A direction in the cone of half-angle `alpha` around unit `axis`, uniform in solid angle
/// when `disk` is uniform on the unit disk: 1 − cos θ = |disk|² (1 − cos α), written with
/// 2 sin²(α/2) so that tiny cones (the sun: 0.00465 rad) keep their precision.
glm::dvec3 inCone(const glm::dvec3& axis, double alpha, const glm::dvec2& disk) {
    const double r2 = glm::dot(disk, disk);
    if (alpha <= 0.0 || r2 <= 0.0) return axis;
    const double s = std::sin(0.5 * alpha);
    const double oneMinusCos = r2 * 2.0 * s * s;
    const double cosTheta = 1.0 - oneMinusCos;
    const double sinTheta = std::sqrt(std::max(oneMinusCos * (2.0 - oneMinusCos), 0.0));
    const glm::dvec3 t1 = anyPerpendicular(axis);
    const glm::dvec3 t2 = glm::cross(axis, t1);
    const glm::dvec2 phi = disk / std::sqrt(r2);
    return glm::normalize(sinTheta * (phi.x * t1 + phi.y * t2) + cosTheta * axis);
}

}  // namespace

bool Emitter::isPointLike() const { return type == LightType::Directional ? angularRadius <= 0.0 : radius <= 0.0; }

std::optional<Emitter> emitterOf(const World& world, Entity light) {
    const Light* l = world.tryGet<Light>(light);
    const WorldTransform* wt = world.tryGet<WorldTransform>(light);
    if (l == nullptr || wt == nullptr || !wt->finite) return std::nullopt;
    Emitter e;
    e.type = l->type;
    e.wsPosition = glm::dvec3(wt->worldFromLocal[3]);
    // The renderer's rule (lightPose), so that both agree on a node of scale 0.
    e.wsTowardLight = worldOrientation(*wt)[2];
    const double radius = std::isfinite(l->radius) ? l->radius : 0.0;
    const double angle = std::isfinite(l->angularRadius) ? l->angularRadius : 0.0;
    e.radius = std::clamp(radius, 0.0, kMaxRadius);
    e.angularRadius = std::clamp(angle, 0.0, kMaxAngularRadius);
    if (e.type == LightType::Directional) {
        e.clamped = e.angularRadius != static_cast<double>(l->angularRadius);
    } else {
        e.clamped = e.radius != static_cast<double>(l->radius);
    }
    return e;
}

ShadowRayAim aimAtEmitter(const Emitter& emitter, const glm::dvec3& wsPoint, const glm::dvec2& disk) {
    switch (emitter.type) {
        case LightType::Directional:
            return {inCone(emitter.wsTowardLight, emitter.angularRadius, disk),
                    std::numeric_limits<double>::infinity()};
        case LightType::Spot:
            return aimAtPoint(wsPoint, onDisk(emitter.wsPosition, emitter.wsTowardLight, emitter.radius, disk));
        case LightType::Point: {
            const glm::dvec3 toCenter = emitter.wsPosition - wsPoint;
            const double d = glm::length(toCenter);
            const double r = emitter.radius;
            if (r <= 0.0) return aimAtPoint(wsPoint, emitter.wsPosition);
            if (d <= r) return {};  // inside the emitting sphere: nothing lies between
            const glm::dvec3 w = toCenter / d;
            const double k = r / d;
            const glm::dvec3 silhouetteCenter = wsPoint + w * (d * (1.0 - k * k));
            return aimAtPoint(wsPoint, onDisk(silhouetteCenter, w, r * std::sqrt(1.0 - k * k), disk));
        }
    }
    return {};
}

glm::dvec2 multiJitteredSample(std::uint32_t index, std::uint32_t count, std::uint32_t pattern) {
    // Kensler's cmj() with aspect 1: an m x n grid, m = floor(sqrt(N)), n = ceil(N / m).
    const auto m = static_cast<std::uint32_t>(std::sqrt(static_cast<double>(count)));
    const std::uint32_t n = (count + m - 1) / m;
    const std::uint32_t s = permute(index, count, pattern * 0x51633e2du);
    const std::uint32_t sx = permute(s % m, m, pattern * 0x68bc21ebu);
    const std::uint32_t sy = permute(s / m, n, pattern * 0x02e5be93u);
    const double jx = randomUnit(s, pattern * 0x967a889bu);
    const double jy = randomUnit(s, pattern * 0x368cc8b7u);
    return {(sx + (sy + jx) / n) / m, (s + jy) / count};
}

glm::dvec2 concentricDisk(const glm::dvec2& square) {
    const double a = 2.0 * square.x - 1.0;
    const double b = 2.0 * square.y - 1.0;
    if (a == 0.0 && b == 0.0) return glm::dvec2(0.0);
    constexpr double kQuarterPi = 0.25 * std::numbers::pi;
    double r = 0.0;
    double phi = 0.0;
    if (std::abs(a) > std::abs(b)) {
        r = a;
        phi = kQuarterPi * (b / a);
    } else {
        r = b;
        phi = 2.0 * kQuarterPi - kQuarterPi * (a / b);
    }
    return {r * std::cos(phi), r * std::sin(phi)};
}

std::uint32_t patternId(std::uint32_t seed, std::uint64_t pixel, std::uint32_t light) {
    const std::uint64_t h = splitMix64(splitMix64(splitMix64(seed) ^ pixel) ^ light);
    return static_cast<std::uint32_t>(h ^ (h >> 32));
}

}  // namespace shadow::reference
