#include <shadow/reference.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <mutex>
#include <limits>
#include <optional>
#include <tuple>
#include <utility>
#include <thread>

#include "emitters.h"
#include "ray_scene.h"

namespace shadow::reference {
namespace {

constexpr int kMaxImageSize = 16384;
constexpr int kMaxSamples = 1 << 20;
constexpr int kMaxThreads = 1024;
/// Positions mode: the surface under a given position is looked for on the camera ray within
/// this fraction of the camera distance on either side of it.
constexpr double kSurfaceSearchWindow = 1e-3;

/// The point a pixel shades.
struct ShadingPoint {
    bool covered = false;    ///< on geometry (else background)
    bool receives = true;    ///< the surface receives shadows
    bool hasNormal = false;  ///< positions mode without a surface found: false
    glm::dvec3 wsPosition{0.0};
    glm::dvec3 wsNormal{0.0};  ///< unit geometric normal when `hasNormal`
    double epsilon = 0.0;      ///< shadow-ray offset (m): the hit's, see ray_scene.h
};

struct Estimate {
    double visibility = 1.0;
    double standardError = 0.0;
};

/// The fraction of `rays` shadow rays from `point` to the emitter that no caster blocks.
Estimate estimateVisibility(const RayScene& scene, const Emitter& emitter, const ShadingPoint& point, int rays,
                            std::uint32_t pattern) {
    const double eps = point.epsilon;
    int unoccluded = 0;
    for (int k = 0; k < rays; ++k) {
        const glm::dvec2 disk = rays == 1
                                    ? glm::dvec2(0.0)
                                    : concentricDisk(multiJitteredSample(static_cast<std::uint32_t>(k),
                                                                         static_cast<std::uint32_t>(rays), pattern));
        const ShadowRayAim aim = aimAtEmitter(emitter, point.wsPosition, disk);
        if (!(aim.distance > 0.0)) {  // on or inside the emitter: nothing in between
            ++unoccluded;
            continue;
        }
        glm::dvec3 origin = point.wsPosition;
        double tnear = 0.0;
        if (point.hasNormal) {
            const double side = glm::dot(point.wsNormal, aim.direction) >= 0.0 ? 1.0 : -1.0;
            origin += point.wsNormal * (side * eps);
        } else {
            tnear = eps;
        }
        glm::dvec3 direction = aim.direction;
        double tfar = aim.distance;
        if (std::isfinite(aim.distance)) {
            // Aim from the offset origin at the very emitter sample.
            const glm::dvec3 toTarget = point.wsPosition + aim.direction * aim.distance - origin;
            tfar = glm::length(toTarget);
            direction = toTarget / tfar;
            tfar -= eps;
        }
        if (!(tfar > tnear) || !scene.occluded(origin, direction, tnear, tfar)) ++unoccluded;
    }
    Estimate e;
    e.visibility = static_cast<double>(unoccluded) / rays;
    e.standardError = binomialStandardError(e.visibility, rays);
    return e;
}

}  // namespace

Status checkPositions(const ImageF& positions) {
    if (positions.channels != 4) return Error{ErrorCode::MalformedFile, "positions: expected 4 channels (R, G, B, A)"};
    for (int y = 0; y < positions.height; ++y) {
        for (int x = 0; x < positions.width; ++x) {
            if (!(positions.at(x, y, 3) >= 0.5f)) continue;
            for (int c = 0; c < 3; ++c) {
                if (!std::isfinite(positions.at(x, y, c))) {
                    return Error{ErrorCode::InvalidValue, "positions: pixel (" + std::to_string(x) + ", " +
                                                              std::to_string(y) +
                                                              ") is covered but its position is not finite"};
                }
            }
        }
    }
    return Ok{};
}

namespace {

Status validate(const ReferenceOptions& o) {
    if (o.width < 1 || o.height < 1 || o.width > kMaxImageSize || o.height > kMaxImageSize) {
        return Error{ErrorCode::InvalidArgument, "size " + std::to_string(o.width) + "x" + std::to_string(o.height) +
                                                     ": width and height must be in [1, 16384]"};
    }
    if (o.samples < 1 || o.samples > kMaxSamples) {
        return Error{ErrorCode::InvalidArgument, "samples " + std::to_string(o.samples) + ": must be in [1, 1048576]"};
    }
    if (o.threads < 0 || o.threads > kMaxThreads) {
        return Error{ErrorCode::InvalidArgument, "threads " + std::to_string(o.threads) + ": must be in [0, 1024]"};
    }
    if (const ImageF* p = o.wsPositions; p != nullptr) {
        if (Status s = checkPositions(*p); !s) return s;
        if (p->width != o.width || p->height != o.height) {
            return Error{ErrorCode::MismatchedInputs, "positions: image is " + std::to_string(p->width) + "x" +
                                                          std::to_string(p->height) + ", expected " +
                                                          std::to_string(o.width) + "x" + std::to_string(o.height)};
        }
    }
    return Ok{};
}

/// Everything the workers share; each pixel is written by exactly one worker.
class Tracer {
public:
    Tracer(const RayScene& scene, const CameraView& camera, const ReferenceOptions& options,
           const std::vector<std::optional<Emitter>>& emitters, const std::vector<const Light*>& lights,
           ReferenceResult& out)
        : scene_(scene), camera_(camera), options_(options), emitters_(emitters), lights_(lights), out_(out) {
        shaded_.assign(static_cast<std::size_t>(options.width) * options.height, 0);
        rowEpsilon_.assign(static_cast<std::size_t>(options.height), {std::numeric_limits<double>::infinity(), 0.0});
    }

    /// Rows are handed out one at a time so the threads stay busy until the end.
    void work() {
        for (int y = nextRow_++; y < options_.height; y = nextRow_++) {
            for (int x = 0; x < options_.width; ++x) tracePixel(x, y);
            const int done = ++rowsDone_;
            if (options_.progress) {
                const std::lock_guard<std::mutex> lock(progressMutex_);
                options_.progress(done, options_.height);
            }
        }
    }

    [[nodiscard]] const std::vector<std::uint8_t>& shaded() const { return shaded_; }
    /// The smallest and largest shadow-ray offset of the shaded pixels (0, 0 without any).
    [[nodiscard]] std::pair<double, double> epsilonRange() const {
        std::pair<double, double> range{std::numeric_limits<double>::infinity(), 0.0};
        for (const auto& [low, high] : rowEpsilon_) {
            range.first = std::min(range.first, low);
            range.second = std::max(range.second, high);
        }
        return range.second > 0.0 ? range : std::pair<double, double>{0.0, 0.0};
    }
    [[nodiscard]] int positionsWithoutSurface() const { return withoutSurface_.load(); }
    [[nodiscard]] int positionsBeyondReach() const { return beyondReach_.load(); }

private:
    ShadingPoint fromCamera(int x, int y) const {
        const CameraRay ray = cameraRay(camera_, options_.width, options_.height, x + 0.5, y + 0.5);
        ShadingPoint p;
        const std::optional<SurfaceHit> hit = scene_.intersect(ray.wsOrigin, ray.direction, ray.tnear, ray.tfar);
        if (!hit) return p;
        p.covered = true;
        p.receives = hit->receivesShadows;
        p.hasNormal = true;
        p.wsPosition = hit->wsPosition;
        p.wsNormal = hit->wsNormal;
        p.epsilon = hit->epsilon;
        return p;
    }

    ShadingPoint fromPositions(int x, int y) {
        const ImageF& image = *options_.wsPositions;
        ShadingPoint p;
        if (!(image.at(x, y, 3) >= 0.5f)) return p;
        p.wsPosition = glm::dvec3(image.at(x, y, 0), image.at(x, y, 1), image.at(x, y, 2));
        if (!insideWorld(p.wsPosition)) {
            // No surface of a scene can be there, and rays from there are beyond float tracing.
            ++beyondReach_;
            p.wsPosition = glm::dvec3(0.0);
            return p;
        }
        p.covered = true;
        p.epsilon = scene_.epsilonAt(p.wsPosition);
        // The surface under the position: the camera ray through it, searched only near it so
        // a surface just in front (a silhouette the rasteriser decided otherwise) is skipped.
        const glm::dvec3 toPoint = p.wsPosition - camera_.wsPosition;
        if (glm::length(toPoint) > 0.0) {
            const std::optional<SurfaceHit> hit =
                scene_.intersect(camera_.wsPosition, toPoint, 1.0 - kSurfaceSearchWindow, 1.0 + kSurfaceSearchWindow);
            if (hit) {
                p.receives = hit->receivesShadows;
                p.hasNormal = true;
                p.wsNormal = hit->wsNormal;
                p.epsilon = std::max(p.epsilon, hit->epsilon);
                return p;
            }
        }
        ++withoutSurface_;
        return p;
    }

    /// Whether light `i`'s Blinn-Phong term is non-zero at `p` (the engine's shading rule:
    /// normal turned towards the camera, N·L > 0 towards the light's centre, spot cone, range).
    bool lightReaches(std::size_t i, const ShadingPoint& p) const {
        const Emitter& e = *emitters_[i];
        const Light* light = lights_[i];
        if (light == nullptr || !p.hasNormal) return true;
        glm::dvec3 n = p.wsNormal;
        if (glm::dot(n, camera_.wsPosition - p.wsPosition) < 0.0) n = -n;
        glm::dvec3 toLight = e.wsTowardLight;
        double distance = 0.0;
        if (e.type != LightType::Directional) {
            toLight = e.wsPosition - p.wsPosition;
            distance = glm::length(toLight);
            if (!(distance > 0.0)) return true;
            toLight /= distance;
        }
        if (glm::dot(n, toLight) <= 0.0) return false;
        if (e.type != LightType::Directional && light->range > 0.0f && distance >= light->range) return false;
        if (e.type == LightType::Spot &&
            glm::dot(-toLight, -e.wsTowardLight) <= std::cos(static_cast<double>(light->outerConeAngle))) {
            return false;
        }
        return true;
    }

    void tracePixel(int x, int y) {
        const ShadingPoint p = options_.wsPositions != nullptr ? fromPositions(x, y) : fromCamera(x, y);
        if (p.covered) {
            for (int c = 0; c < 3; ++c) out_.wsPosition.at(x, y, c) = static_cast<float>(p.wsPosition[c]);
            out_.wsPosition.at(x, y, 3) = 1.0f;
        }
        if (!p.covered || !p.receives) return;  // images are initialised to V = 1, SE = 0
        const std::uint64_t pixel = static_cast<std::uint64_t>(y) * options_.width + x;
        shaded_[pixel] = 1;
        auto& [low, high] = rowEpsilon_[static_cast<std::size_t>(y)];  // each row has one worker
        low = std::min(low, p.epsilon);
        high = std::max(high, p.epsilon);
        for (std::size_t i = 0; i < emitters_.size(); ++i) {
            if (!emitters_[i]) continue;
            const Emitter& e = *emitters_[i];
            const int rays = e.isPointLike() ? 1 : options_.samples;
            const Estimate v =
                estimateVisibility(scene_, e, p, rays, patternId(options_.seed, pixel, static_cast<std::uint32_t>(i)));
            out_.visibility[i].at(x, y, 0) = static_cast<float>(v.visibility);
            out_.standardError[i].at(x, y, 0) = static_cast<float>(v.standardError);
            out_.lit[i].at(x, y, 0) = lightReaches(i, p) ? 1.0f : 0.0f;
        }
    }

    const RayScene& scene_;
    const CameraView& camera_;
    const ReferenceOptions& options_;
    const std::vector<std::optional<Emitter>>& emitters_;
    const std::vector<const Light*>& lights_;
    ReferenceResult& out_;
    std::vector<std::uint8_t> shaded_;
    std::vector<std::pair<double, double>> rowEpsilon_;  ///< per row: smallest, largest offset
    std::atomic<int> nextRow_{0};
    std::atomic<int> rowsDone_{0};
    std::atomic<int> withoutSurface_{0};
    std::atomic<int> beyondReach_{0};
    std::mutex progressMutex_;
};

/// Per-light means and maxima over the shaded pixels.
void summarise(const std::vector<std::uint8_t>& shaded, ReferenceResult& out) {
    for (std::size_t i = 0; i < out.lights.size(); ++i) {
        LightReference& light = out.lights[i];
        double sumSe = 0.0;
        double sumV = 0.0;
        double maxSe = 0.0;
        std::size_t n = 0;
        for (std::size_t p = 0; p < shaded.size(); ++p) {
            if (shaded[p] == 0) continue;
            const double se = out.standardError[i].pixels[p];
            sumSe += se;
            sumV += out.visibility[i].pixels[p];
            maxSe = std::max(maxSe, se);
            ++n;
        }
        light.meanStandardError = n > 0 ? sumSe / static_cast<double>(n) : 0.0;
        light.maxStandardError = maxSe;
        light.meanVisibility = n > 0 ? sumV / static_cast<double>(n) : 1.0;
    }
}

double secondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

double binomialStandardError(double v, int rays) {
    return rays > 0 ? std::sqrt(std::clamp(v * (1.0 - v), 0.0, 0.25) / rays) : 0.0;
}

CameraRay cameraRay(const CameraView& camera, int width, int height, double px, double py) {
    // NDC of the image point; image rows run top-down, NDC y bottom-up (the renderer flips
    // rows on readback).
    const double ndcX = 2.0 * px / width - 1.0;
    const double ndcY = 1.0 - 2.0 * py / height;
    // glm::perspective: x_ndc = x_view / (-z_view · tan(yfov/2) · aspect), likewise y without
    // aspect.
    const double tanHalf = std::tan(0.5 * static_cast<double>(camera.yfov));
    const glm::dvec3 vsDirection(ndcX * tanHalf * camera.aspect, ndcY * tanHalf, -1.0);
    const glm::dmat3 worldFromView(glm::inverse(camera.viewFromWorld));
    CameraRay ray;
    ray.wsOrigin = camera.wsPosition;
    ray.direction = worldFromView * vsDirection;
    ray.tnear = camera.znear;
    ray.tfar = camera.zfar;
    return ray;
}

Result<ReferenceResult> traceVisibility(Scene& scene, const CameraView& camera, const ReferenceOptions& options) {
    if (Status s = validate(options); !s) return s.error();

    const auto buildStart = std::chrono::steady_clock::now();
    Result<RayScene> rays = RayScene::build(scene.world);
    if (!rays) return rays.error();

    ReferenceResult out;
    out.buildSeconds = secondsSince(buildStart);
    std::vector<std::optional<Emitter>> emitters;
    std::vector<const Light*> lights;
    for (const Entity light : scene.lights) {
        emitters.push_back(emitterOf(scene.world, light));
        lights.push_back(scene.world.tryGet<Light>(light));
        LightReference& report = out.lights.emplace_back();
        report.missing = !emitters.back();
        report.sizeClamped = emitters.back() && emitters.back()->clamped;
        report.raysPerPixel = !emitters.back() ? 0 : emitters.back()->isPointLike() ? 1 : options.samples;
    }
    out.wsPosition = makeImage(options.width, options.height, 4);
    for (std::size_t i = 0; i < emitters.size(); ++i) {
        ImageF v = makeImage(options.width, options.height, 1);
        std::fill(v.pixels.begin(), v.pixels.end(), 1.0f);
        out.visibility.push_back(std::move(v));
        out.standardError.push_back(makeImage(options.width, options.height, 1));
        out.lit.push_back(makeImage(options.width, options.height, 1));  // 0 off receivers
    }

    int threads = options.threads > 0 ? options.threads : static_cast<int>(std::thread::hardware_concurrency());
    threads = std::clamp(threads, 1, options.height);
    out.threads = threads;

    const auto traceStart = std::chrono::steady_clock::now();
    Tracer tracer(*rays, camera, options, emitters, lights, out);
    {
        std::vector<std::jthread> workers;
        for (int t = 1; t < threads; ++t) workers.emplace_back([&tracer] { tracer.work(); });
        tracer.work();
    }  // joins
    out.traceSeconds = secondsSince(traceStart);

    summarise(tracer.shaded(), out);
    std::tie(out.epsilonMin, out.epsilonMax) = tracer.epsilonRange();
    for (std::size_t p = 0; p < tracer.shaded().size(); ++p) {
        const bool covered = out.wsPosition.pixels[p * 4 + 3] > 0.5f;
        out.coveredPixels += covered ? 1 : 0;
        out.nonReceiverPixels += covered && tracer.shaded()[p] == 0 ? 1 : 0;
    }
    out.positionsWithoutSurface = tracer.positionsWithoutSurface();
    out.positionsBeyondReach = tracer.positionsBeyondReach();
    return out;
}

}  // namespace shadow::reference
