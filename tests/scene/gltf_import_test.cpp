// Tests of loadGltf (engine/src/scene/gltf_import.cpp and its helpers). Every test writes its
// own glTF into a fresh directory: JSON built with nlohmann::json and binary data embedded as
// base64 data URIs (or an external .bin), and .glb files written by tinygltf's own writer.
#include <gtest/gtest.h>
#include <shadow/scene.h>
#include <tiny_gltf.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "scene/shadow_extras.h"

namespace shadow {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

constexpr int kFloat = 5126;
constexpr int kUnsignedShort = 5123;

/// Directories made by `testDir` in this process.
std::vector<fs::path>& createdDirs() {
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
[[maybe_unused]] ::testing::Environment* const kRemoveTestDirs =
    ::testing::AddGlobalTestEnvironment(new RemoveTestDirs);

/// A fresh directory for the running test, under SHADOW_TEST_TMP when set. The process id
/// keeps concurrent runs apart.
fs::path testDir() {
    const char* env = std::getenv("SHADOW_TEST_TMP");
    const fs::path root =
        (env != nullptr && *env != '\0') ? fs::path(env) : fs::temp_directory_path();
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    const fs::path dir = root / ("gltf_" + std::string(info->test_suite_name()) + "_" +
                                 info->name() + "_" + std::to_string(::getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
    createdDirs().push_back(dir);
    return dir;
}

std::string base64(const std::vector<unsigned char>& bytes) {
    static const char* const kAlphabet =
        "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
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

void writeText(const fs::path& path, const std::string& text) {
    std::ofstream(path, std::ios::binary) << text;
}

std::string readBytes(const fs::path& path) {
    std::string bytes(fs::file_size(path), '\0');
    std::ifstream(path, std::ios::binary)
        .read(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    return bytes;
}

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
        return push(
            "bufferViews",
            {{"buffer", 0}, {"byteOffset", offset}, {"byteLength", data.size() * sizeof(T)}});
    }
    int accessor(int bufferView, int componentType, std::size_t count, const std::string& type) {
        return push("accessors", {{"bufferView", bufferView},
                                  {"componentType", componentType},
                                  {"count", count},
                                  {"type", type}});
    }
    int floats(const std::vector<float>& v, const std::string& type) {
        const std::size_t n = type == "SCALAR" ? 1 : type == "VEC3" ? 3 : 4;
        return accessor(view(v), kFloat, v.size() / n, type);
    }
    int indices(const std::vector<std::uint16_t>& v) {
        return accessor(view(v), kUnsignedShort, v.size(), "SCALAR");
    }
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
            const std::string uri =
                binName.empty() ? "data:application/octet-stream;base64," + base64(bin) : binName;
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
fs::path convertToGlb(const fs::path& gltf, const fs::path& glb) {
    tinygltf::TinyGLTF io;
    tinygltf::Model model;
    std::string err, warn;
    EXPECT_TRUE(io.LoadASCIIFromFile(&model, &err, &warn, gltf.string())) << err;
    EXPECT_TRUE(io.WriteGltfSceneToFile(&model, glb.string(), true, true, false, true));
    return glb;
}

Entity findByName(Scene& scene, const std::string& name) {
    Entity found;
    scene.world.view<Name>().each([&](Entity e, Name& n) {
        if (n.value == name) found = e;
    });
    return found;
}

/// Loads `path` expecting failure; returns the message.
std::string loadError(const fs::path& path) {
    const Result<Scene> result = loadGltf(path.string());
    EXPECT_FALSE(result.ok());
    return result.ok() ? std::string() : result.error().message;
}

void expectVec3(const glm::dvec3& actual, const glm::dvec3& expected, double eps = 1e-6) {
    EXPECT_NEAR(actual.x, expected.x, eps);
    EXPECT_NEAR(actual.y, expected.y, eps);
    EXPECT_NEAR(actual.z, expected.z, eps);
}

/// Same rotation (q and -q are the same).
void expectSameRotation(const glm::dquat& a, const glm::dquat& b) {
    EXPECT_NEAR(std::abs(glm::dot(a, b)), 1.0, 1e-6);
}

#define EXPECT_MESSAGE(message, part) \
    EXPECT_NE((message).find(part), std::string::npos) << "message: " << (message)

// ---- valid scenes -------------------------------------------------------------------------

TEST(GltfImport, LoadsTriangleMeshWithMaterial) {
    Doc doc;
    doc.push("materials", {{"pbrMetallicRoughness",
                            {{"baseColorFactor", {0.5, 0.25, 1.0, 1.0}},
                             {"metallicFactor", 0.5},
                             {"roughnessFactor", 0.5}}}});
    doc.node({{"name", "tri"}, {"mesh", doc.triangleMesh(0)}});
    doc.scene({0});
    auto scene = loadGltf(doc.write(testDir() / "tri_scene.gltf").string());
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    EXPECT_EQ(scene->name, "tri_scene");
    const Entity e = findByName(*scene, "tri");
    ASSERT_TRUE(scene->world.has<Mesh>(e));
    const MeshData& mesh = *scene->world.get<Mesh>(e).data;
    ASSERT_EQ(mesh.positions.size(), 3u);
    EXPECT_EQ(mesh.indices, (std::vector<std::uint32_t>{0, 1, 2}));
    expectVec3(mesh.normals[1], {0, 0, 1});
    expectVec3(mesh.bounds.min, {0, 0, 0});
    expectVec3(mesh.bounds.max, {1, 1, 0});
    const Material& m = scene->world.get<Material>(e);
    expectVec3(m.albedo, {0.5, 0.25, 1.0});
    expectVec3(m.specular, {0.27, 0.145, 0.52});  // mix(0.04, base, 0.5)
    EXPECT_NEAR(m.shininess, 30.0f, 1e-3f);       // 2 / 0.5^4 - 2
}

TEST(GltfImport, GeneratesFlatNormalsAndSequentialIndicesWhenMissing) {
    Doc doc;
    const int pos = doc.floats({0, 0, 0, 1, 0, 0, 0, 0, -1}, "VEC3");  // faces +Y
    doc.push("meshes", {{"primitives", json::array({{{"attributes", {{"POSITION", pos}}}}})}});
    doc.node({{"name", "floor"}, {"mesh", 0}});
    auto scene = loadGltf(doc.write(testDir() / "s.gltf").string());
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    const MeshData& mesh = *scene->world.get<Mesh>(findByName(*scene, "floor")).data;
    EXPECT_EQ(mesh.indices, (std::vector<std::uint32_t>{0, 1, 2}));
    ASSERT_EQ(mesh.normals.size(), 3u);
    expectVec3(mesh.normals[0], {0, 1, 0});
    const Material& m = scene->world.get<Material>(findByName(*scene, "floor"));
    EXPECT_EQ(m.shininess, Material{}.shininess);  // no material: the default
}

TEST(GltfImport, BuildsNodeHierarchyFromChosenSceneOnly) {
    Doc doc;
    doc.node({{"name", "root"}, {"translation", {1, 2, 3}}, {"children", {1}}});
    doc.node({{"rotation", {0, std::sin(0.25 * M_PI), 0, std::cos(0.25 * M_PI)}}});
    doc.node({{"name", "elsewhere"}});
    doc.scene({0});
    auto scene = loadGltf(doc.write(testDir() / "s.gltf").string());
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    EXPECT_EQ(scene->world.size(), 2u);
    const Entity root = findByName(*scene, "root");
    const Entity child = findByName(*scene, "node1");  // unnamed nodes are named by index
    ASSERT_TRUE(scene->world.alive(child));
    EXPECT_TRUE(scene->world.get<Transform>(root).parent.isNull());
    EXPECT_EQ(scene->world.get<Transform>(child).parent, root);
    expectVec3(scene->world.get<Transform>(root).translation, {1, 2, 3});
    expectSameRotation(scene->world.get<Transform>(child).rotation,
                       glm::angleAxis(0.5 * M_PI, glm::dvec3(0, 1, 0)));
    EXPECT_FALSE(scene->world.alive(findByName(*scene, "elsewhere")));
}

TEST(GltfImport, DecomposesNodeMatrixIntoTrs) {
    Doc doc;  // T(1,2,3) * R_y(90 deg) * S(2), column-major
    doc.node({{"name", "m"}, {"matrix", {0, 0, -2, 0, 0, 2, 0, 0, 2, 0, 0, 0, 1, 2, 3, 1}}});
    auto scene = loadGltf(doc.write(testDir() / "s.gltf").string());
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    const Transform& t = scene->world.get<Transform>(findByName(*scene, "m"));
    expectVec3(t.translation, {1, 2, 3});
    expectVec3(t.scale, {2, 2, 2});
    expectSameRotation(t.rotation, glm::angleAxis(0.5 * M_PI, glm::dvec3(0, 1, 0)));
}

TEST(GltfImport, DecomposesMirroredMatrixAndRejectsSingularOne) {
    Doc doc;
    doc.node({{"name", "mirror"}, {"matrix", {-1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}}});
    auto scene = loadGltf(doc.write(testDir() / "s.gltf").string());
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    const Transform& t = scene->world.get<Transform>(findByName(*scene, "mirror"));
    glm::dmat3 m = glm::mat3_cast(t.rotation);  // recompose R * S
    for (int c = 0; c < 3; ++c) m[c] *= t.scale[c];
    EXPECT_NEAR(m[0][0], -1.0, 1e-9);
    EXPECT_NEAR(m[1][1], 1.0, 1e-9);
    EXPECT_NEAR(m[2][2], 1.0, 1e-9);

    doc.j["nodes"][0]["matrix"] = {0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    EXPECT_MESSAGE(loadError(doc.write(testDir() / "s.gltf")),
                   "nodes[0].matrix: cannot be decomposed into translation, rotation and scale");
}

TEST(GltfImport, ImportsPerspectiveCamerasInNodeOrder) {
    Doc doc;
    doc.push("cameras", {{"type", "perspective"},
                         {"perspective",
                          {{"yfov", 0.9}, {"znear", 0.1}, {"zfar", 50.0}, {"aspectRatio", 1.5}}}});
    doc.push("cameras",
             {{"type", "perspective"}, {"perspective", {{"yfov", 0.5}, {"znear", 0.2}}}});
    doc.node({{"name", "first"}, {"camera", 1}});
    doc.node({{"name", "second"}, {"camera", 0}});
    auto scene = loadGltf(doc.write(testDir() / "s.gltf").string());
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    ASSERT_EQ(scene->cameras.size(), 2u);
    EXPECT_EQ(scene->cameras[0], findByName(*scene, "first"));
    const Camera& infinite = scene->world.get<Camera>(scene->cameras[0]);
    EXPECT_FLOAT_EQ(infinite.yfov, 0.5f);
    EXPECT_FLOAT_EQ(infinite.zfar, 1e4f);  // no zfar: "infinite"
    EXPECT_FLOAT_EQ(infinite.aspectRatio, 0.0f);
    const Camera& full = scene->world.get<Camera>(scene->cameras[1]);
    EXPECT_FLOAT_EQ(full.znear, 0.1f);
    EXPECT_FLOAT_EQ(full.zfar, 50.0f);
    EXPECT_FLOAT_EQ(full.aspectRatio, 1.5f);
}

/// Directional PCSS, spot PCF, point with technique none, point without extras.
Doc lightsDoc() {
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
    doc.light(
        {{"type", "point"}, {"extras", {{"shadow", {{"technique", "none"}, {"radius", 0.1}}}}}});
    doc.light({{"type", "point"}});
    for (int i = 0; i < 4; ++i) {
        doc.node({{"name", "light" + std::to_string(i)},
                  {"extensions", {{"KHR_lights_punctual", {{"light", i}}}}}});
    }
    return doc;
}

TEST(GltfImport, ImportsAllLightTypesWithShadowExtras) {
    Doc doc = lightsDoc();
    auto scene = loadGltf(doc.write(testDir() / "s.gltf").string());
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    ASSERT_EQ(scene->lights.size(), 4u);
    World& w = scene->world;
    const Light& sun = w.get<Light>(scene->lights[0]);
    EXPECT_EQ(sun.type, LightType::Directional);
    expectVec3(sun.color, {1.0, 0.5, 0.25});
    EXPECT_FLOAT_EQ(sun.intensity, 3.0f);
    EXPECT_FLOAT_EQ(sun.angularRadius, 0.01f);
    const Shadow& sunShadow = w.get<Shadow>(scene->lights[0]);
    EXPECT_EQ(sunShadow.technique, ShadowTechnique::Pcss);
    EXPECT_EQ(sunShadow.mapSize, 2048);
    EXPECT_EQ(sunShadow.cascades, 3);
    EXPECT_FLOAT_EQ(sunShadow.cascadeSplitLambda, 0.5f);
    EXPECT_FLOAT_EQ(sunShadow.shadowDistance, 80.0f);

    const Light& spot = w.get<Light>(scene->lights[1]);
    EXPECT_EQ(spot.type, LightType::Spot);
    EXPECT_FLOAT_EQ(spot.range, 20.0f);
    EXPECT_FLOAT_EQ(spot.innerConeAngle, 0.2f);
    EXPECT_FLOAT_EQ(spot.outerConeAngle, 0.6f);
    EXPECT_FLOAT_EQ(spot.radius, 0.25f);
    const Shadow& spotShadow = w.get<Shadow>(scene->lights[1]);
    EXPECT_EQ(spotShadow.technique, ShadowTechnique::Pcf);
    EXPECT_EQ(spotShadow.pcfSamples, 32);
    EXPECT_EQ(spotShadow.blockerSamples, 8);
    EXPECT_FLOAT_EQ(spotShadow.pcfRadius, 0.1f);
    EXPECT_FLOAT_EQ(spotShadow.maxFilterTexels, 16.0f);
    EXPECT_FLOAT_EQ(spotShadow.constantBias, 0.01f);
    EXPECT_FLOAT_EQ(spotShadow.slopeBias, 2.0f);
    EXPECT_FLOAT_EQ(spotShadow.normalOffset, 0.5f);
    EXPECT_FLOAT_EQ(spotShadow.nearPlane, 0.3f);

    EXPECT_EQ(w.get<Light>(scene->lights[2]).type, LightType::Point);
    EXPECT_FLOAT_EQ(w.get<Light>(scene->lights[2]).radius, 0.1f);
    EXPECT_FALSE(w.has<Shadow>(scene->lights[2]));  // technique none: no shadow map at all
    const Shadow& defaults = w.get<Shadow>(scene->lights[3]);
    EXPECT_EQ(defaults.technique, ShadowTechnique::Hard);
    EXPECT_EQ(defaults.mapSize, Shadow{}.mapSize);
}

TEST(GltfImport, OrdersLightsDepthFirstFromSceneRoots) {
    Doc doc;
    for (int i = 0; i < 5; ++i) doc.light({{"type", "point"}});
    const auto lit = [](const char* name, int light) {
        return json{{"name", name}, {"extensions", {{"KHR_lights_punctual", {{"light", light}}}}}};
    };
    json a = lit("a", 0), c = lit("c", 2);
    a["children"] = {1, 2};
    c["children"] = {3};
    doc.node(a);
    doc.node(lit("b", 1));
    doc.node(c);
    doc.node(lit("d", 3));
    doc.node(lit("e", 4));
    doc.scene({4, 0});
    auto scene = loadGltf(doc.write(testDir() / "s.gltf").string());
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    std::vector<std::string> order;
    for (Entity e : scene->lights) order.push_back(scene->world.get<Name>(e).value);
    EXPECT_EQ(order, (std::vector<std::string>{"e", "a", "b", "c", "d"}));
}

TEST(GltfImport, ReadsMeshShadowFlagsAndSharesMeshData) {
    Doc doc;
    const int mesh = doc.triangleMesh();
    doc.node({{"name", "noCast"}, {"mesh", mesh}, {"extras", {{"shadow", {{"cast", false}}}}}});
    doc.node(
        {{"name", "noReceive"}, {"mesh", mesh}, {"extras", {{"shadow", {{"receive", false}}}}}});
    auto scene = loadGltf(doc.write(testDir() / "s.gltf").string());
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    const Mesh& a = scene->world.get<Mesh>(findByName(*scene, "noCast"));
    const Mesh& b = scene->world.get<Mesh>(findByName(*scene, "noReceive"));
    EXPECT_FALSE(a.castShadows);
    EXPECT_TRUE(a.receiveShadows);
    EXPECT_TRUE(b.castShadows);
    EXPECT_FALSE(b.receiveShadows);
    EXPECT_EQ(a.data.get(), b.data.get());
}

TEST(GltfImport, SplitsPrimitivesIntoChildEntitiesAndSkipsNonTriangles) {
    Doc doc;
    const int pos = doc.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3");
    const json tri = {{"attributes", {{"POSITION", pos}}}};
    const json points = {{"attributes", {{"POSITION", pos}}}, {"mode", 0}};
    doc.push("meshes", {{"primitives", json::array({tri, points, tri})}});
    doc.node({{"name", "multi"}, {"mesh", 0}});
    auto scene = loadGltf(doc.write(testDir() / "s.gltf").string());
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    const Entity multi = findByName(*scene, "multi");
    EXPECT_FALSE(scene->world.has<Mesh>(multi));
    for (const char* name : {"multi/primitive0", "multi/primitive1"}) {
        const Entity part = findByName(*scene, name);
        ASSERT_TRUE(scene->world.has<Mesh>(part)) << name;
        EXPECT_EQ(scene->world.get<Transform>(part).parent, multi);
    }
    EXPECT_FALSE(scene->world.alive(findByName(*scene, "multi/primitive2")));
}

/// Animation 0 (2 s): LINEAR translation (0..2 s) and STEP scale of node 0. Animation 1 (4 s):
/// CUBICSPLINE translation of node 1 (0..2 s) and LINEAR rotation of node 0 (0..4 s).
Doc animatedDoc() {
    Doc doc;
    doc.node({{"name", "a"}});
    doc.node({{"name", "b"}});
    const int t02 = doc.floats({0, 2}, "SCALAR");
    const int t01 = doc.floats({0, 1}, "SCALAR");
    const int t04 = doc.floats({0, 4}, "SCALAR");
    const auto sampler = [](int in, int out, const char* interpolation) {
        return json{{"input", in}, {"output", out}, {"interpolation", interpolation}};
    };
    const auto channel = [](int s, int node, const char* path) {
        return json{{"sampler", s}, {"target", {{"node", node}, {"path", path}}}};
    };
    doc.push("animations", {{"samplers",
                             {sampler(t02, doc.floats({0, 0, 0, 2, 4, 6}, "VEC3"), "LINEAR"),
                              sampler(t01, doc.floats({1, 1, 1, 3, 3, 3}, "VEC3"), "STEP")}},
                            {"channels", {channel(0, 0, "translation"), channel(1, 0, "scale")}}});
    const float s = static_cast<float>(std::sin(0.25 * M_PI));
    const int cubic = doc.floats({0, 0, 0, 0, 0, 0, 1, 0, 0,  /* key 0: in, value, out */
                                  0, 0, 0, 1, 0, 0, 0, 0, 0}, /* key 1 */
                                 "VEC3");
    doc.push("animations",
             {{"samplers",
               {sampler(t02, cubic, "CUBICSPLINE"),
                sampler(t04, doc.floats({0, 0, 0, 1, 0, s, 0, s}, "VEC4"), "LINEAR")}},
              {"channels", {channel(0, 1, "translation"), channel(1, 0, "rotation")}}});
    return doc;
}

TEST(GltfImport, ImportsAnimationChannelsThatAnimateAsSampled) {
    Doc doc = animatedDoc();
    auto scene = loadGltf(doc.write(testDir() / "s.gltf").string());
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    World& w = scene->world;
    const Entity a = findByName(*scene, "a");
    const Entity b = findByName(*scene, "b");
    EXPECT_DOUBLE_EQ(scene->animationDuration, 4.0);
    EXPECT_DOUBLE_EQ(w.get<Animation>(a).duration, 4.0);  // longest animation targeting it
    EXPECT_DOUBLE_EQ(w.get<Animation>(b).duration, 4.0);  // its animation's last key is at 4 s
    EXPECT_EQ(w.get<Animation>(a).channels.size(), 3u);

    animate(w, 0.5);
    expectVec3(w.get<Transform>(a).translation, {0.5, 1.0, 1.5});
    expectVec3(w.get<Transform>(a).scale, {1, 1, 1});  // STEP holds key 0 until t = 1
    animate(w, 1.0);
    expectVec3(w.get<Transform>(a).scale, {3, 3, 3});
    // Hermite with dt = 2, out-tangent 1 at key 0: x(u=0.5) = 2 * 0.125 + 0.5.
    expectVec3(w.get<Transform>(b).translation, {0.75, 0, 0});
    animate(w, 2.0);  // 45 deg of the 90 deg turn over 4 s
    expectSameRotation(w.get<Transform>(a).rotation,
                       glm::angleAxis(0.25 * M_PI, glm::dvec3(0, 1, 0)));
    animate(w, 3.0);  // after the last translation key: held
    expectVec3(w.get<Transform>(a).translation, {2, 4, 6});
    animate(w, 4.5);  // wraps: 4.5 mod 4 = 0.5
    expectVec3(w.get<Transform>(a).translation, {0.5, 1.0, 1.5});
    animate(w, 5.0);  // b loops with animation 1: 5 mod 4 = 1
    expectVec3(w.get<Transform>(b).translation, {0.75, 0, 0});
    animate(w, 3.0);  // b holds its last key from 2 s to the end of its 4 s animation
    expectVec3(w.get<Transform>(b).translation, {1, 0, 0});
}

TEST(GltfImport, GlbRoundTripMatchesGltf) {
    const fs::path dir = testDir();
    Doc doc = lightsDoc();
    doc.node({{"name", "tri"}, {"mesh", doc.triangleMesh()}});
    const fs::path gltf = doc.write(dir / "scene.gltf");
    const fs::path glb = convertToGlb(gltf, dir / "scene.glb");
    ASSERT_EQ(readBytes(glb).substr(0, 4), "glTF");
    auto fromText = loadGltf(gltf.string());
    auto fromBinary = loadGltf(glb.string());
    ASSERT_TRUE(fromText.ok()) << fromText.error().message;
    ASSERT_TRUE(fromBinary.ok()) << fromBinary.error().message;
    EXPECT_EQ(fromBinary->name, "scene");
    EXPECT_EQ(fromBinary->world.size(), fromText->world.size());
    ASSERT_EQ(fromBinary->lights.size(), 4u);
    EXPECT_EQ(fromBinary->world.get<Shadow>(fromBinary->lights[0]).mapSize, 2048);
    const MeshData& mesh = *fromBinary->world.get<Mesh>(findByName(*fromBinary, "tri")).data;
    EXPECT_EQ(mesh.positions,
              fromText->world.get<Mesh>(findByName(*fromText, "tri")).data->positions);
}

TEST(GltfImport, LoadsExternalBuffer) {
    Doc doc;
    doc.node({{"name", "tri"}, {"mesh", doc.triangleMesh()}});
    auto scene = loadGltf(doc.write(testDir() / "s.gltf", "s.bin").string());
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    EXPECT_EQ(scene->world.get<Mesh>(findByName(*scene, "tri")).data->indices.size(), 3u);
}

// ---- bad files: each error names the element at fault ---------------------------------

TEST(GltfImport, RejectsMissingFile) {
    EXPECT_NE(loadError(testDir() / "absent.gltf").find("absent.gltf"), std::string::npos);
}

TEST(GltfImport, RejectsTruncatedGltf) {
    Doc doc;
    doc.node({{"mesh", doc.triangleMesh()}});
    const fs::path path = doc.write(testDir() / "cut.gltf");
    const std::string text = readBytes(path);
    writeText(path, text.substr(0, text.size() / 2));
    EXPECT_NE(loadError(path).find("cut.gltf: "), std::string::npos);
}

TEST(GltfImport, RejectsTruncatedGlb) {
    const fs::path dir = testDir();
    Doc doc;
    doc.node({{"mesh", doc.triangleMesh()}});
    const fs::path glb = convertToGlb(doc.write(dir / "s.gltf"), dir / "cut.glb");
    const std::string bytes = readBytes(glb);
    writeText(glb, bytes.substr(0, bytes.size() / 2));
    EXPECT_NE(loadError(glb).find("cut.glb: "), std::string::npos);
}

TEST(GltfImport, RejectsGlbWithWrongMagic) {
    const fs::path dir = testDir();
    Doc doc;
    doc.node({{"mesh", doc.triangleMesh()}});
    const fs::path glb = convertToGlb(doc.write(dir / "s.gltf"), dir / "magic.glb");
    std::string bytes = readBytes(glb);
    bytes[0] = 'x';
    writeText(glb, bytes);
    const std::string message = loadError(glb);
    EXPECT_NE(message.find("magic.glb: "), std::string::npos) << message;
    EXPECT_NE(message.find("magic is not \"glTF\""), std::string::npos) << message;
}

/// A document with one triangle mesh on node 0, then `edit` applied to its JSON.
template <typename Edit>
std::string errorAfterEdit(Edit edit) {
    Doc doc;
    doc.node({{"name", "n"}, {"mesh", doc.triangleMesh()}});
    edit(doc);
    return loadError(doc.write(testDir() / "bad.gltf"));
}

TEST(GltfImport, RejectsAccessorOutOfBounds) {
    const std::string m = errorAfterEdit([](Doc& d) { d.j["accessors"][0]["count"] = 4; });
    EXPECT_MESSAGE(m,
                   "bad.gltf: meshes[0].primitives[0].attributes.POSITION: accessors[0]: "
                   "exceeds bufferViews[0]");
}

TEST(GltfImport, RejectsBufferViewOutsideBuffer) {
    const std::string m = errorAfterEdit([](Doc& d) { d.j["bufferViews"][0]["byteOffset"] = 60; });
    EXPECT_MESSAGE(m, "bufferViews[0]: exceeds buffers[0]");
}

TEST(GltfImport, RejectsIndexOutOfRange) {
    const std::string m = errorAfterEdit([](Doc& d) {
        d.j["meshes"][0]["primitives"][0]["indices"] = d.indices({0, 1, 3});
    });
    EXPECT_MESSAGE(m, "meshes[0].primitives[0].indices: accessors[3]: index 3");
}

TEST(GltfImport, RejectsPositionsThatAreNotFloatVec3) {
    const std::string m = errorAfterEdit([](Doc& d) { d.j["accessors"][0]["type"] = "VEC4"; });
    EXPECT_MESSAGE(m, "accessors[0]: must be FLOAT VEC3");
}

TEST(GltfImport, RejectsNanInPositions) {
    const std::string m = errorAfterEdit([](Doc& d) {
        const float nan = std::numeric_limits<float>::quiet_NaN();
        d.j["meshes"][0]["primitives"][0]["attributes"]["POSITION"] =
            d.floats({0, 0, 0, nan, 0, 0, 0, 1, 0}, "VEC3");
    });
    EXPECT_MESSAGE(m, "attributes.POSITION: accessors[3]: element 1 not finite");
}

TEST(GltfImport, RejectsNanInNodeRotation) {
    // JSON has no NaN: tinygltf's writer turns it into null, which is what such files hold.
    tinygltf::Model model;
    tinygltf::Node node;
    node.rotation = {0.0, std::nan(""), 0.0, 1.0};
    model.nodes.push_back(node);
    const fs::path path = testDir() / "nan.gltf";
    tinygltf::TinyGLTF io;
    ASSERT_TRUE(io.WriteGltfSceneToFile(&model, path.string(), true, true, false, false));
    EXPECT_MESSAGE(loadError(path), "nan.gltf: nodes[0].rotation");
}

TEST(GltfImport, RejectsCycleInNodeGraph) {
    Doc doc;
    doc.node({{"children", {1}}});
    doc.node({{"children", {0}}});
    EXPECT_MESSAGE(loadError(doc.write(testDir() / "s.gltf")),
                   "is part of a cycle in the node graph");
}

TEST(GltfImport, RejectsNodeWithTwoParents) {
    Doc doc;
    doc.node({{"children", {2}}});
    doc.node({{"children", {2}}});
    doc.node(json::object());
    EXPECT_MESSAGE(loadError(doc.write(testDir() / "s.gltf")),
                   "nodes[2]: has two parents, nodes[0] and nodes[1]");
}

TEST(GltfImport, RejectsReferencesOutOfRange) {
    EXPECT_MESSAGE(errorAfterEdit([](Doc& d) { d.j["nodes"][0]["children"] = {7}; }),
                   "nodes[0].children: node 7 does not exist");
    EXPECT_MESSAGE(errorAfterEdit([](Doc& d) { d.j["nodes"][0]["mesh"] = 3; }),
                   "nodes[0].mesh: mesh 3 does not exist");
    EXPECT_MESSAGE(errorAfterEdit([](Doc& d) {
                       d.j["nodes"][0]["extensions"]["KHR_lights_punctual"]["light"] = 0;
                   }),
                   "nodes[0].extensions.KHR_lights_punctual.light: light 0 does not exist");
    EXPECT_MESSAGE(errorAfterEdit([](Doc& d) {
                       d.scene({0, 5});
                   }),
                   "scenes[0].nodes: node 5 does not exist");
}

TEST(GltfImport, RejectsOrthographicCamera) {
    Doc doc;
    doc.push("cameras",
             {{"type", "orthographic"},
              {"orthographic", {{"xmag", 1}, {"ymag", 1}, {"znear", 0.1}, {"zfar", 10}}}});
    doc.node({{"camera", 0}});
    EXPECT_MESSAGE(loadError(doc.write(testDir() / "s.gltf")),
                   "cameras[0]: orthographic cameras are not supported");
}

TEST(GltfImport, RejectsMissingExternalBuffer) {
    const fs::path dir = testDir();
    Doc doc;
    doc.node({{"mesh", doc.triangleMesh()}});
    const fs::path path = doc.write(dir / "ext.gltf", "gone.bin");
    fs::remove(dir / "gone.bin");
    const std::string message = loadError(path);
    EXPECT_MESSAGE(message, "ext.gltf: ");
    EXPECT_MESSAGE(message, "gone.bin");
}

/// A file with one point light whose `extras.shadow` is `shadow`.
std::string lightShadowError(const json& shadow) {
    Doc doc;
    doc.light({{"type", "point"}});
    doc.light({{"type", "point"}, {"extras", {{"shadow", shadow}}}});
    doc.node({{"extensions", {{"KHR_lights_punctual", {{"light", 1}}}}}});
    return loadError(doc.write(testDir() / "light.gltf"));
}

TEST(GltfImport, RejectsUnknownShadowTechnique) {
    EXPECT_MESSAGE(lightShadowError({{"technique", "vsm"}}),
                   "light.gltf: KHR_lights_punctual.lights[1].extras.shadow.technique: "
                   "unknown technique \"vsm\"");
}

TEST(GltfImport, RejectsNegativeMapSize) {
    EXPECT_MESSAGE(
        lightShadowError({{"mapSize", -512}}),
        "KHR_lights_punctual.lights[1].extras.shadow.mapSize: must be a positive integer");
}

TEST(GltfImport, RejectsStringWhereNumberDue) {
    EXPECT_MESSAGE(lightShadowError({{"pcfRadius", "wide"}}),
                   "KHR_lights_punctual.lights[1].extras.shadow.pcfRadius: must be a number");
    Doc doc;
    doc.light({{"type", "spot"}, {"intensity", "bright"}, {"spot", json::object()}});
    EXPECT_MESSAGE(loadError(doc.write(testDir() / "s.gltf")),
                   "KHR_lights_punctual.lights[0].intensity: must be a number");
}

TEST(GltfImport, RejectsNonIncreasingKeyTimes) {
    Doc doc = animatedDoc();
    doc.j["animations"][0]["samplers"][0]["input"] = doc.floats({1, 1}, "SCALAR");
    EXPECT_MESSAGE(loadError(doc.write(testDir() / "s.gltf")),
                   "animations[0].samplers[0].input: key times not strictly increasing at key 1");
}

TEST(GltfImport, RejectsCubicSplineWithOneValuePerKey) {
    Doc doc = animatedDoc();
    doc.j["animations"][0]["samplers"][0]["interpolation"] = "CUBICSPLINE";
    EXPECT_MESSAGE(loadError(doc.write(testDir() / "s.gltf")),
                   "animations[0].samplers[0].output: has 2 values for 2 keys (expected 6)");
}

TEST(GltfImport, RejectsNanInAnimationKeys) {
    Doc doc = animatedDoc();
    doc.j["animations"][0]["samplers"][0]["output"] =
        doc.floats({0, 0, 0, 2, std::numeric_limits<float>::infinity(), 6}, "VEC3");
    EXPECT_MESSAGE(loadError(doc.write(testDir() / "s.gltf")),
                   "animations[0].samplers[0].output: accessors[");
}

// ---- the extras parsers on their own, as a fuzzer drives them ---------------------------

tinygltf::Value object(tinygltf::Value::Object members) {
    return tinygltf::Value(std::move(members));
}

TEST(GltfShadowExtras, RejectsNonFiniteNumbers) {
    const auto extras = object({{"shadow", object({{"radius", tinygltf::Value(std::nan(""))}})}});
    const auto result = gltf::parseShadowExtras(extras, "L");
    ASSERT_FALSE(result.ok());
    EXPECT_EQ(result.error().message, "L.extras.shadow.radius: not finite");
}

TEST(GltfShadowExtras, AcceptsIntegralRealAsInteger) {
    const auto extras = object({{"shadow", object({{"mapSize", tinygltf::Value(512.0)}})}});
    const auto result = gltf::parseShadowExtras(extras, "L");
    ASSERT_TRUE(result.ok()) << result.error().message;
    EXPECT_EQ(result->shadow.mapSize, 512);
    EXPECT_FALSE(gltf::parseShadowExtras(
                     object({{"shadow", object({{"mapSize", tinygltf::Value(1e12)}})}}), "L")
                     .ok());
}

TEST(GltfShadowExtras, RejectsShadowThatIsNotAnObjectButIgnoresOtherExtras) {
    const auto bad = gltf::parseShadowExtras(object({{"shadow", tinygltf::Value(true)}}), "L");
    ASSERT_FALSE(bad.ok());
    EXPECT_EQ(bad.error().message, "L.extras.shadow: must be an object");
    EXPECT_TRUE(gltf::parseShadowExtras(tinygltf::Value(std::string("note")), "L").ok());
    EXPECT_TRUE(gltf::parseShadowExtras(tinygltf::Value(), "L").ok());
}

TEST(GltfShadowExtras, MeshFlagsMustBeBooleans) {
    const auto bad = gltf::parseMeshShadowExtras(
        object({{"shadow", object({{"cast", tinygltf::Value(1)}})}}), "nodes[2]");
    ASSERT_FALSE(bad.ok());
    EXPECT_EQ(bad.error().message, "nodes[2].extras.shadow.cast: must be true or false");
}

}  // namespace
}  // namespace shadow
