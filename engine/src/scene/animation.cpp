// The animation system: keyframed glTF channels, then procedural motion, written into local
// `Transform`s (and `weights` channels into `Morph::weights`).
//
// Sampling follows the glTF 2.0 spec, appendix C: LINEAR (spherical linear for rotations,
// along the shorter arc), STEP, and CUBICSPLINE (cubic Hermite with tangents scaled by the
// key interval; rotations renormalised). Times before the first key hold the first value and
// after the last key the last value. All arithmetic is in double: the clip time is
// fmod(t, duration) of a double `t`, so `t = 1e7` s keeps sub-microsecond precision.
//
// Nothing non-finite is written: a channel whose result is not finite (possible only for
// components built in code with bad keys) leaves the transform as it was.
#include <shadow/scene.h>

#include <algorithm>
#include <cmath>

namespace shadow {
namespace {

using Interpolation = AnimationChannel::Interpolation;
using Path = AnimationChannel::Path;

bool isFinite(const glm::dvec4& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z) && std::isfinite(v.w);
}

/// Unit quaternion (xyzw in a vec4) as glm's wxyz; zero-length or non-finite gives identity.
glm::dquat toUnitQuat(const glm::dvec4& xyzw) {
    const double length = glm::length(xyzw);
    if (!(length > 0.0) || !std::isfinite(length)) return glm::dquat(1.0, 0.0, 0.0, 0.0);
    const glm::dvec4 n = xyzw / length;
    return glm::dquat(n.w, n.x, n.y, n.z);
}

/// Slerp along the shorter arc; falls back to normalised lerp when the two are so close that
/// sin(angle) loses precision.
glm::dquat slerpShortest(const glm::dquat& a, glm::dquat b, double u) {
    double cosAngle = glm::dot(a, b);
    if (cosAngle < 0.0) {
        b = -b;
        cosAngle = -cosAngle;
    }
    if (cosAngle > 0.9995) {
        return glm::normalize(
            glm::dquat(glm::mix(a.w, b.w, u), glm::mix(a.x, b.x, u), glm::mix(a.y, b.y, u), glm::mix(a.z, b.z, u)));
    }
    const double angle = std::acos(cosAngle);
    const double s = std::sin(angle);
    const double wa = std::sin((1.0 - u) * angle) / s;
    const double wb = std::sin(u * angle) / s;
    return glm::normalize(
        glm::dquat(wa * a.w + wb * b.w, wa * a.x + wb * b.x, wa * a.y + wb * b.y, wa * a.z + wb * b.z));
}

/// Where the clip time falls: key `k` and the fraction `u` in [0, 1] towards key `k + 1`.
/// `u` is 0 before the first key and at the last key (k is then the last key).
struct KeySpan {
    std::size_t k = 0;
    double u = 0.0;
    double dt = 0.0;  ///< times[k + 1] - times[k]; 0 when clamped
};

KeySpan locate(const std::vector<float>& times, double t) {
    const std::size_t n = times.size();
    if (!(t > static_cast<double>(times.front()))) return {0, 0.0, 0.0};
    if (t >= static_cast<double>(times.back())) return {n - 1, 0.0, 0.0};
    // First key strictly after t; it exists and is not the first, by the two tests above.
    const auto next =
        std::upper_bound(times.begin(), times.end(), t, [](double value, float key) { return value < key; });
    const std::size_t k = static_cast<std::size_t>(next - times.begin()) - 1;
    if (k + 1 >= n) return {n - 1, 0.0, 0.0};  // unsorted keys built in code
    const double t0 = times[k];
    const double dt = static_cast<double>(times[k + 1]) - t0;
    // Keys built in code may repeat a time; hold the earlier key rather than divide by zero.
    if (!(dt > 0.0)) return {k, 0.0, 0.0};
    return {k, std::clamp((t - t0) / dt, 0.0, 1.0), dt};
}

/// Vec4 `part` of the channel's value `i` (`AnimationChannel::width` vec4s each).
glm::dvec4 value(const AnimationChannel& c, std::size_t i, std::size_t part) {
    return glm::dvec4(c.values[i * c.width + part]);
}

/// Cubic Hermite per glTF: values are stored as (in-tangent, value, out-tangent) per key.
glm::dvec4 hermite(const AnimationChannel& c, const KeySpan& s, std::size_t part) {
    const glm::dvec4 p0 = value(c, 3 * s.k + 1, part);
    if (s.dt == 0.0) return p0;
    const glm::dvec4 m0 = value(c, 3 * s.k + 2, part) * s.dt;
    const glm::dvec4 p1 = value(c, 3 * (s.k + 1) + 1, part);
    const glm::dvec4 m1 = value(c, 3 * (s.k + 1), part) * s.dt;
    const double u = s.u, u2 = u * u, u3 = u2 * u;
    return (2.0 * u3 - 3.0 * u2 + 1.0) * p0 + (u3 - 2.0 * u2 + u) * m0 + (-2.0 * u3 + 3.0 * u2) * p1 + (u3 - u2) * m1;
}

/// Whether `values` has the count the interpolation needs for `times`.
bool wellFormed(const AnimationChannel& c) {
    if (c.times.empty()) return false;
    const std::size_t perKey = c.interpolation == Interpolation::CubicSpline ? 3 : 1;
    return c.width > 0 && c.values.size() >= perKey * c.times.size() * c.width;
}

/// Vec4 `part` of the channel's value at the time `s` locates, rotations as xyzw (not yet
/// normalised).
glm::dvec4 sample(const AnimationChannel& c, const KeySpan& s, std::size_t part = 0) {
    switch (c.interpolation) {
        case Interpolation::Step: return value(c, s.k, part);
        case Interpolation::CubicSpline: return hermite(c, s, part);
        case Interpolation::Linear: break;
    }
    const glm::dvec4 a = value(c, s.k, part);
    if (s.dt == 0.0) return a;
    const glm::dvec4 b = value(c, s.k + 1, part);
    if (c.path != Path::Rotation) return glm::mix(a, b, s.u);
    const glm::dquat q = slerpShortest(toUnitQuat(a), toUnitQuat(b), s.u);
    return glm::dvec4(q.x, q.y, q.z, q.w);
}

/// Writes a `Weights` channel's value into `morph`'s weights (those it has), four at a time.
void applyWeights(const AnimationChannel& c, const KeySpan& s, Morph& morph) {
    for (std::size_t part = 0; part < c.width; ++part) {
        const glm::dvec4 v = sample(c, s, part);
        for (std::size_t k = 0; k < 4 && 4 * part + k < morph.weights.size(); ++k) {
            const double w = v[static_cast<int>(k)];
            if (std::isfinite(w)) morph.weights[4 * part + k] = static_cast<float>(w);
        }
    }
}

void applyChannel(const AnimationChannel& c, double t, Transform& transform, Morph* morph) {
    if (!wellFormed(c)) return;
    const KeySpan s = locate(c.times, t);
    if (c.path == Path::Weights) {
        if (morph != nullptr) applyWeights(c, s, *morph);
        return;
    }
    const glm::dvec4 v = sample(c, s);
    if (!isFinite(v)) return;
    switch (c.path) {
        case Path::Translation: transform.translation = glm::dvec3(v); break;
        case Path::Rotation: transform.rotation = toUnitQuat(v); break;
        case Path::Scale: transform.scale = glm::dvec3(v); break;
        case Path::Weights: break;
    }
}

/// The clip time for absolute time `t`: looping with period `duration`; 0 for clips of no
/// length, where every key time is <= 0 and so the last key holds.
double clipTime(double t, double duration) {
    if (!(duration > 0.0) || !std::isfinite(duration)) return 0.0;
    return std::fmod(t, duration);
}

bool isFinite(const glm::dvec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

void applyMotion(const ProceduralMotion& m, double t, Transform& transform) {
    using Kind = ProceduralMotion::Kind;
    const double angle = m.speed * t + m.phase;
    switch (m.kind) {
        case Kind::Orbit: {
            const glm::dvec3 p = m.center + m.radius * glm::dvec3(std::cos(angle), 0.0, std::sin(angle));
            if (isFinite(p)) transform.translation = p;
            break;
        }
        case Kind::Bob: {
            const glm::dvec3 p = m.center + m.axis * (m.amplitude * std::sin(angle));
            if (isFinite(p)) transform.translation = p;
            break;
        }
        case Kind::Spin: {
            // A zero or non-finite axis names no rotation; the rotation is left as it was.
            const double length = glm::length(m.axis);
            if (!(length > 0.0) || !std::isfinite(length) || !std::isfinite(angle)) break;
            transform.rotation = glm::angleAxis(angle, m.axis / length);
            break;
        }
    }
}

}  // namespace

// Keyframes first, then procedural motion, so an entity with both takes the procedural value
// for whatever the motion writes (Orbit/Bob: translation; Spin: rotation).
void animate(World& world, double t) {
    if (!std::isfinite(t) || t < 0.0) t = 0.0;
    world.view<Transform, Animation>().each([&world, t](Entity e, Transform& transform, Animation& anim) {
        const double local = clipTime(t, anim.duration);
        Morph* morph = world.tryGet<Morph>(e);
        for (const AnimationChannel& channel : anim.channels) applyChannel(channel, local, transform, morph);
    });
    world.view<Transform, ProceduralMotion>().each(
        [t](Entity, Transform& transform, ProceduralMotion& motion) { applyMotion(motion, t, transform); });
}

}  // namespace shadow
