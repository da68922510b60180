// Writing glTF files for the importer's tests (tests/scene/gltf_*_test.cpp,
// shadow_extras_test.cpp): every test writes its own glTF into a fresh directory, JSON built with
// nlohmann::json and binary data embedded as base64 data URIs (or an external .bin), and .glb
// files written by tinygltf's own writer; plus the checks those tests share.
#pragma once

#include <gtest/gtest.h>
#include <shadow/scene.h>
#include <tiny_gltf.h>
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "test_support.h"

namespace shadow::gltf_test {

namespace fs = std::filesystem;
using nlohmann::json;

inline constexpr int kFloat = 5126;
inline constexpr int kUnsignedShort = 5123;

/// Directories made by `testDir` in this process.
inline std::vector<fs::path>& createdDirs() {
    static std::vector<fs::path> dirs;
    return dirs;
}

/// Removes the test directories when the run ends, unless SHADOW_KEEP_TEST_FILES is set
/// (to look at the files a failing test wrote).
class RemoveTestDirs : public ::testing::Environment {
public:
    void TearDown() override {
        if (std::getenv("SHADOW_KEEP_TEST_FILES") != nullptr) return;
        std::error_code ec;
        for (const fs::path& dir : createdDirs()) fs::remove_all(dir, ec);
    }
};
/// Registered once per test binary (an inline variable), whichever files include this header.
inline ::testing::Environment* const kRemoveTestDirs = ::testing::AddGlobalTestEnvironment(new RemoveTestDirs);

/// A fresh directory for the running test, under SHADOW_TEST_TMP when set. The process id
/// keeps concurrent runs apart.
inline fs::path testDir() {
    const char* env = std::getenv("SHADOW_TEST_TMP");
    const fs::path root = (env != nullptr && *env != '\0') ? fs::path(env) : fs::temp_directory_path();
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    const fs::path dir =
        root / ("gltf_" + std::string(info->test_suite_name()) + "_" + info->name() + "_" + std::to_string(::getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
    createdDirs().push_back(dir);
    return dir;
}

inline std::string base64(const std::vector<unsigned char>& bytes) {
    static const char* const kAlphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    for (std::size_t i = 0; i < bytes.size(); i += 3) {
        const std::size_t n = std::min<std::size_t>(3, bytes.size() - i);
        std::uint32_t v = 0;
        for (std::size_t k = 0; k < 3; ++k) v = (v << 8) | (k < n ? bytes[i + k] : 0u);
        for (std::size_t k = 0; k < 4; ++k) {
            out += k <= n ? kAlphabet[(v >> (18 - 6 * k)) & 63u] : '=';
        }
    }
    return out;
}

inline void writeText(const fs::path& path, const std::string& text) { std::ofstream(path, std::ios::binary) << text; }

using test::readBytes;

/// A glTF document under construction, with one binary buffer.
struct Doc {
    json j = {{"asset", {{"version", "2.0"}}}};
    std::vector<unsigned char> bin;

    template <typename T>
    int view(const std::vector<T>& data) {
        while (bin.size() % 4 != 0) bin.push_back(0);
        const std::size_t offset = bin.size();
        const auto* bytes = reinterpret_cast<const unsigned char*>(data.data());
        bin.insert(bin.end(), bytes, bytes + data.size() * sizeof(T));
        return push("bufferViews", {{"buffer", 0}, {"byteOffset", offset}, {"byteLength", data.size() * sizeof(T)}});
    }
    int accessor(int bufferView, int componentType, std::size_t count, const std::string& type) {
        return push("accessors",
                    {{"bufferView", bufferView}, {"componentType", componentType}, {"count", count}, {"type", type}});
    }
    int floats(const std::vector<float>& v, const std::string& type) {
        const std::size_t n = type == "SCALAR" ? 1 : type == "VEC3" ? 3 : 4;
        return accessor(view(v), kFloat, v.size() / n, type);
    }
    int indices(const std::vector<std::uint16_t>& v) { return accessor(view(v), kUnsignedShort, v.size(), "SCALAR"); }
    int push(const char* array, const json& value) {
        j[array].push_back(value);
        return static_cast<int>(j[array].size()) - 1;
    }
    int node(const json& n) { return push("nodes", n); }
    int light(const json& l) {
        j["extensions"]["KHR_lights_punctual"]["lights"].push_back(l);
        return static_cast<int>(j["extensions"]["KHR_lights_punctual"]["lights"].size()) - 1;
    }
    void scene(const std::vector<int>& roots) {
        j["scenes"] = json::array({{{"nodes", roots}}});
        j["scene"] = 0;
    }
    /// A one-triangle mesh in the XY plane, facing +Z.
    int triangleMesh(int material = -1) {
        json primitive = {{"attributes",
                           {{"POSITION", floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3")},
                            {"NORMAL", floats({0, 0, 1, 0, 0, 1, 0, 0, 1}, "VEC3")}}},
                          {"indices", indices({0, 1, 2})}};
        if (material >= 0) primitive["material"] = material;
        return push("meshes", {{"primitives", json::array({primitive})}});
    }
    /// Writes the document with its buffer as a base64 data URI (or as `binName` beside it).
    fs::path write(const fs::path& path, const std::string& binName = "") {
        if (!bin.empty()) {
            const std::string uri = binName.empty() ? "data:application/octet-stream;base64," + base64(bin) : binName;
            j["buffers"] = json::array({{{"byteLength", bin.size()}, {"uri", uri}}});
            if (!binName.empty()) {
                writeText(path.parent_path() / binName, std::string(bin.begin(), bin.end()));
            }
        }
        writeText(path, j.dump(2));
        return path;
    }
};

/// Rewrites a .gltf as .glb with tinygltf's writer.
inline fs::path convertToGlb(const fs::path& gltf, const fs::path& glb) {
    tinygltf::TinyGLTF io;
    tinygltf::Model model;
    std::string err, warn;
    EXPECT_TRUE(io.LoadASCIIFromFile(&model, &err, &warn, gltf.string())) << err;
    EXPECT_TRUE(io.WriteGltfSceneToFile(&model, glb.string(), true, true, false, true));
    return glb;
}

inline Entity findByName(Scene& scene, const std::string& name) {
    Entity found;
    scene.world.view<Name>().each([&](Entity e, Name& n) {
        if (n.value == name) found = e;
    });
    return found;
}

/// Loads `path` expecting failure; returns the message.
/// Expects `w` to be the warning of `code` about `element` with the whole `message`.
inline void expectWarning(const Warning& w, WarningCode code, const std::string& element, const std::string& message) {
    EXPECT_EQ(w.code, code) << w.message;
    EXPECT_EQ(w.element, element);
    EXPECT_EQ(w.message, message);
}

inline std::string loadError(const fs::path& path) {
    const Result<Scene> result = loadGltf(path.string());
    EXPECT_FALSE(result.ok());
    return result.ok() ? std::string() : result.error().message;
}

inline void expectVec3(const glm::dvec3& actual, const glm::dvec3& expected, double eps = 1e-6) {
    EXPECT_NEAR(actual.x, expected.x, eps);
    EXPECT_NEAR(actual.y, expected.y, eps);
    EXPECT_NEAR(actual.z, expected.z, eps);
}

/// Same rotation (q and -q are the same).
inline void expectSameRotation(const glm::dquat& a, const glm::dquat& b) {
    EXPECT_NEAR(std::abs(glm::dot(a, b)), 1.0, 1e-6);
}

#define EXPECT_MESSAGE(message, part) EXPECT_NE((message).find(part), std::string::npos) << "message: " << (message)

/// A 1 m square sheet in the XZ plane (x, z in [-0.5, 0.5], facing +Y) on node 0 ("sheet", at
/// y = 1), with one morph target that moves its +x edge by +1 m in x (at weight w the sheet spans
/// x in [-0.5, 0.5 + w]) and turns its normals nowhere; mesh weights {`weight`}. With `animated`,
/// animations[0] drives the weight from 0 at t = 0 to 1 at t = 2 s by `interpolation`.
inline Doc morphSheetDoc(float weight, bool animated = false, const std::string& interpolation = "LINEAR") {
    Doc doc;
    const int position = doc.floats({-0.5f, 0, -0.5f, 0.5f, 0, -0.5f, 0.5f, 0, 0.5f, -0.5f, 0, 0.5f}, "VEC3");
    const int normal = doc.floats({0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0}, "VEC3");
    const int delta = doc.floats({0, 0, 0, 1, 0, 0, 1, 0, 0, 0, 0, 0}, "VEC3");
    json primitive = {{"attributes", {{"POSITION", position}, {"NORMAL", normal}}},
                      {"indices", doc.indices({0, 2, 1, 0, 3, 2})},
                      {"targets", json::array({{{"POSITION", delta}}})}};
    doc.push("meshes", {{"primitives", json::array({primitive})}, {"weights", {weight}}});
    doc.node({{"name", "sheet"}, {"mesh", 0}, {"translation", {0, 1, 0}}});
    doc.scene({0});
    if (animated) {
        const bool cubic = interpolation == "CUBICSPLINE";
        // CUBICSPLINE: zero tangents, so the weight eases (smoothstep) from 0 to 1.
        const int output =
            doc.floats(cubic ? std::vector<float>{0, 0, 0, 0, 1, 0} : std::vector<float>{0, 1}, "SCALAR");
        doc.push(
            "animations",
            {{"samplers",
              json::array(
                  {{{"input", doc.floats({0, 2}, "SCALAR")}, {"output", output}, {"interpolation", interpolation}}})},
             {"channels", json::array({{{"sampler", 0}, {"target", {{"node", 0}, {"path", "weights"}}}}})}});
    }
    return doc;
}

/// `morphSheetDoc`'s sheet with `targets` targets, each moving the +x edge by 0.1 m, all of
/// weight 0.5 (every one non-zero), its mesh named "fan".
inline Doc manyTargetsSheetDoc(std::size_t targets) {
    Doc doc = morphSheetDoc(0.5f);
    json& mesh = doc.j["meshes"][0];
    mesh["name"] = "fan";
    const int delta = doc.floats({0, 0, 0, 0.1f, 0, 0, 0.1f, 0, 0, 0, 0, 0}, "VEC3");
    mesh["primitives"][0]["targets"] = json::array();
    for (std::size_t k = 0; k < targets; ++k) mesh["primitives"][0]["targets"].push_back({{"POSITION", delta}});
    mesh["weights"] = std::vector<float>(targets, 0.5f);
    return doc;
}

/// Directional PCSS, spot PCF, point with technique none, point without extras.
inline Doc lightsDoc() {
    Doc doc;
    doc.light({{"type", "directional"},
               {"color", {1.0, 0.5, 0.25}},
               {"intensity", 3.0},
               {"extras",
                {{"shadow",
                  {{"technique", "pcss"},
                   {"mapSize", 2048},
                   {"angularRadius", 0.01},
                   {"cascades", 3},
                   {"cascadeSplitLambda", 0.5},
                   {"shadowDistance", 80},
                   {"futureKnob", "ignored"}}}}}});
    doc.light({{"type", "spot"},
               {"range", 20},
               {"spot", {{"innerConeAngle", 0.2}, {"outerConeAngle", 0.6}}},
               {"extras",
                {{"shadow",
                  {{"technique", "pcf"},
                   {"radius", 0.25},
                   {"pcfRadius", 0.1},
                   {"pcfSamples", 32},
                   {"blockerSamples", 8},
                   {"maxFilterTexels", 16},
                   {"constantBias", 0.01},
                   {"slopeBias", 2},
                   {"normalOffset", 0.5},
                   {"nearPlane", 0.3}}}}}});
    doc.light({{"type", "point"}, {"extras", {{"shadow", {{"technique", "none"}, {"radius", 0.1}}}}}});
    doc.light({{"type", "point"}});
    for (int i = 0; i < 4; ++i) {
        doc.node({{"name", "light" + std::to_string(i)}, {"extensions", {{"KHR_lights_punctual", {{"light", i}}}}}});
    }
    return doc;
}

}  // namespace shadow::gltf_test
