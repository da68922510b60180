// What the glTF fuzzer does with one input: the importer from memory (strict and lenient),
// the CPU half of a frame on whatever scene loads (animation, transforms and skin poses, shadow
// planning, with the skins' and the planner's invariants checked), and the extras.shadow parsers on the input read as
// JSON. Shared by tests/fuzz/gltf_fuzzer.cpp and the GoogleTest that replays
// tests/fuzz/regressions/ and tests/fuzz/corpus/ in every ordinary build.
//
// Header-only on purpose: tests/CMakeLists.txt globs only *_test.cpp files.
#pragma once

#include <shadow/scene.h>
#include <shadow/shadow_system.h>
#include <tiny_gltf.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>

#include "scene/gltf_import.h"
#include "scene/shadow_extras.h"

namespace shadow::fuzz {

/// Aborts (the fuzzer's crash) when a promise of the engine is broken.
inline void check(bool ok, const char* what) {
    if (ok) return;
    std::fprintf(stderr, "fuzz target: broken invariant: %s\n", what);
    std::abort();
}

/// A JSON value as tinygltf holds it; nesting deeper than `maxDepth` becomes null.
inline tinygltf::Value toValue(const nlohmann::json& j, int maxDepth = 64) {
    if (maxDepth <= 0) return {};
    switch (j.type()) {
        case nlohmann::json::value_t::boolean: return tinygltf::Value(j.get<bool>());
        case nlohmann::json::value_t::number_integer:
        case nlohmann::json::value_t::number_unsigned: {
            const double d = j.get<double>();
            if (std::abs(d) < 2147483647.0) return tinygltf::Value(static_cast<int>(d));
            return tinygltf::Value(d);
        }
        case nlohmann::json::value_t::number_float: return tinygltf::Value(j.get<double>());
        case nlohmann::json::value_t::string: return tinygltf::Value(j.get<std::string>());
        case nlohmann::json::value_t::array: {
            tinygltf::Value::Array a;
            for (const nlohmann::json& e : j) a.push_back(toValue(e, maxDepth - 1));
            return tinygltf::Value(std::move(a));
        }
        case nlohmann::json::value_t::object: {
            tinygltf::Value::Object o;
            for (const auto& [key, e] : j.items()) o.emplace(key, toValue(e, maxDepth - 1));
            return tinygltf::Value(std::move(o));
        }
        default: return {};
    }
}

/// True when every element is a finite float.
inline bool finiteAsFloat(const glm::dmat4& m) {
    const glm::mat4 f(m);
    for (int c = 0; c < 4; ++c) {
        for (int r = 0; r < 4; ++r) {
            if (!std::isfinite(f[c][r])) return false;
        }
    }
    return true;
}

/// The CPU half of a few frames of `scene`, checking what the skins and the shadow planner
/// promise: a posed skin's matrices finite as the floats the GPU gets; layer
/// matrices finite even as the floats the GPU gets (made relative to the camera), finite
/// positive depth ranges, sizes inside the limits and the memory budget.
inline void runCpuFrames(Scene& scene) {
    (void)updateTransforms(scene.world);
    const Entity camera = scene.cameras.empty() ? addDefaultCamera(scene) : scene.cameras.front();
    ShadowPlanner planner;
    const ShadowLimits limits{4096, 2048, std::int64_t{1} << 26};
    planner.setLimits(limits);
    for (double t : {0.0, 0.37, 1e7}) {
        animate(scene.world, t);
        (void)updateTransforms(scene.world);
        scene.world.view<Skin>().each([](Entity, const Skin& skin) {
            if (!skin.posed) return;
            check(skin.frameFromMesh.size() == skin.joints.size(), "a posed skin has a matrix per joint");
            check(finiteAsFloat(skin.worldFromFrame), "a posed skin's frame is finite");
            for (const glm::mat4& m : skin.frameFromMesh) {
                check(finiteAsFloat(glm::dmat4(m)), "a posed skin's joint matrices are finite floats");
            }
        });
        const CameraView view = makeCameraView(scene.world, camera, 16.0f / 9.0f);
        const glm::dmat4 worldFromCs = glm::translate(glm::dmat4(1.0), view.wsPosition);
        const ShadowFrame& frame = planner.prepare(scene.world, view, scene.lights);
        std::int64_t bytes = 0;
        check(frame.lights.size() == scene.lights.size(), "one plan per scene light");
        for (const ShadowLightPlan& plan : frame.lights) {
            check(plan.hasMap() ? plan.mapSize >= 1 && plan.mapSize <= limits.maxTextureSize : plan.mapSize == 0,
                  "map size inside the limits");
            for (const ShadowLayerPlan& layer : plan.layers) {
                check(finiteAsFloat(layer.lightFromWorld * worldFromCs) && finiteAsFloat(layer.clipFromLight),
                      "layer matrices finite as the GPU's floats");
                check(std::isfinite(layer.depthScale) && layer.depthScale > 0.0f, "positive finite depth scale");
                check(std::isfinite(layer.depthNear) && layer.depthNear >= 0.0f, "finite depth near");
            }
            bytes += shadowMapBytes(plan.technique(), plan.mapSize, static_cast<int>(plan.layers.size()),
                                    plan.settings.maxFilterTexels);
        }
        check(bytes <= limits.maxShadowBytes, "maps inside the memory budget");
    }
}

/// One fuzz input. Never throws; aborts only on a broken invariant (or a sanitizer report).
inline void runOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view bytes(reinterpret_cast<const char*>(data), size);
    for (bool strict : {true, false}) {
        GltfLoadOptions options;
        options.strictShadowSettings = strict;
        Result<Scene> scene = gltf::loadGltfFromMemory(bytes, "fuzz.gltf", options);
        if (scene.ok()) runCpuFrames(*scene);
    }
    const nlohmann::json j = nlohmann::json::parse(bytes.begin(), bytes.end(), nullptr, /*allow_exceptions=*/false);
    if (j.is_discarded()) return;
    const tinygltf::Value value = toValue(j);
    (void)gltf::parseShadowExtras(value, "fuzz");
    (void)gltf::parseMeshShadowExtras(value, "fuzz");
    const tinygltf::Value wrapped(tinygltf::Value::Object{{"shadow", value}});
    (void)gltf::parseShadowExtras(wrapped, "fuzz");
    (void)gltf::parseMeshShadowExtras(wrapped, "fuzz");
}

}  // namespace shadow::fuzz
