// loadGltf: a glTF 2.0 file (.gltf with embedded or external buffers, or .glb) to a Scene.
//
// tinygltf parses the JSON and the GLB container; everything it does not check is checked
// here before use (accessor ranges, index values, finiteness, node graph shape, index
// references), and every problem is an `Error` of the form `<file>: <element>: <problem>`.
//
// Entities: one per node of the chosen scene (the file's `scene`, else scenes[0], else every
// root node in index order). Nodes are visited depth-first, pre-order: the scene's roots in
// the order the scene lists them, each node's children in the order of its `children` array.
// `Scene::lights` and `Scene::cameras` are in that visiting order (so `visibility_<i>.exr`
// numbers light instances in it). Nodes outside the chosen scene are validated but not
// instantiated.
//
// A mesh node whose mesh has one drawable primitive carries `Mesh` and `Material` itself;
// with several, each primitive becomes a child entity `<node>/primitive<k>`. Instances of one
// glTF mesh share its `MeshData`.
//
// Not supported (ignored): skins, morph targets, textures (images are never decoded),
// orthographic cameras (an error when a node uses one), sparse accessors (an error when used).
#include "scene/gltf_import.h"

#include <shadow/scene.h>
#include <tiny_gltf.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <glm/gtc/constants.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <glm/gtx/matrix_decompose.hpp>
#include <initializer_list>
#include <limits>
#include <optional>
#include <string_view>

#include "scene/gltf_animation.h"
#include "scene/gltf_lights.h"
#include "scene/gltf_mesh.h"
#include "scene/gltf_values.h"
#include "scene/shadow_extras.h"

namespace shadow {
namespace {

using gltf::elementError;
using gltf::indexed;

// ---- reading the file -------------------------------------------------------------------

/// The engine uses no textures: accept every image without decoding it.
bool skipImage(tinygltf::Image*, const int, std::string*, std::string*, int, int, const unsigned char*, int, void*) {
    return true;
}

/// tinygltf's default expands URIs with wordexp(3), a shell-like expansion; URIs are file
/// names, not shell words, so take them literally.
std::string literalPath(const std::string& path, void*) { return path; }

/// tinygltf messages end in newlines and may hold several lines; make them one line.
std::string oneLine(std::string text) {
    std::replace(text.begin(), text.end(), '\n', ' ');
    while (!text.empty() && std::isspace(static_cast<unsigned char>(text.back()))) text.pop_back();
    return text.empty() ? "could not be parsed" : text;
}

bool hasBinaryMagic(const std::string& path) {
    std::ifstream file(path, std::ios::binary);
    char magic[4] = {};
    return file.read(magic, 4) && std::string(magic, 4) == "glTF";
}

std::string lowerExtension(const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return ext;
}

/// In-memory input reads no file: an external buffer URI is an error, not a disk access.
bool noFileExists(const std::string&, void*) { return false; }
bool noFileRead(std::vector<unsigned char>*, std::string* err, const std::string& path, void*) {
    if (err != nullptr) *err += "external file \"" + path + "\" is not read when loading from memory\n";
    return false;
}

/// Runs one tinygltf load (`load(loader, model, err, warn)`) with the engine's callbacks:
/// images skipped, URIs literal, and, for in-memory input, no file access at all. Errors start
/// with `name`.
template <typename Load>
Result<tinygltf::Model> parseModel(const std::string& name, bool filesAllowed, Load load) {
    tinygltf::TinyGLTF loader;
    loader.SetImageLoader(&skipImage, nullptr);
    if (filesAllowed) {
        loader.SetFsCallbacks(
            {&tinygltf::FileExists, &literalPath, &tinygltf::ReadWholeFile, &tinygltf::WriteWholeFile, nullptr});
    } else {
        loader.SetFsCallbacks({&noFileExists, &literalPath, &noFileRead, &tinygltf::WriteWholeFile, nullptr});
    }
    tinygltf::Model model;
    std::string err;
    std::string warn;
    bool ok = false;
    try {
        ok = load(loader, model, err, warn);
    } catch (const std::exception& e) {  // tinygltf throws on some malformed input
        err = e.what();
    }
    if (!ok) return Error{name + ": " + oneLine(err)};
    return model;
}

/// Parses the file with tinygltf: binary when it starts with the GLB magic, JSON otherwise.
/// A `.glb` without the magic is an error rather than a JSON parse.
Result<tinygltf::Model> readModel(const std::string& path) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec)) {
        return Error{path + ": no such file"};
    }
    const bool binary = hasBinaryMagic(path);
    if (!binary && lowerExtension(path) == ".glb") {
        return Error{path + ": not a binary glTF file (the header magic is not \"glTF\")"};
    }
    return parseModel(path, true,
                      [&](tinygltf::TinyGLTF& loader, tinygltf::Model& model, std::string& err, std::string& warn) {
                          return binary ? loader.LoadBinaryFromFile(&model, &err, &warn, path)
                                        : loader.LoadASCIIFromFile(&model, &err, &warn, path);
                      });
}

// ---- nodes ------------------------------------------------------------------------------

/// Reads an optional fixed-size number array of a node; `out` is untouched when absent.
template <int N>
Status readNodeArray(const std::vector<double>& values, const std::string& where, double* out) {
    if (values.empty()) return Ok{};
    if (values.size() != N) {
        return elementError(where, "must have " + std::to_string(N) + " numbers");
    }
    for (int i = 0; i < N; ++i) {
        if (!std::isfinite(values[static_cast<std::size_t>(i)])) {
            return elementError(where, "not finite");
        }
        out[i] = values[static_cast<std::size_t>(i)];
    }
    return Ok{};
}

bool allFinite(std::initializer_list<double> values) {
    return std::all_of(values.begin(), values.end(), [](double v) { return std::isfinite(v); });
}

/// The unit quaternion along (x, y, z, w); identity for zero. Divides by the largest
/// component first so that finite but huge values (1e300) do not overflow the length.
glm::dquat unitQuat(double x, double y, double z, double w) {
    const double largest = std::max({std::abs(x), std::abs(y), std::abs(z), std::abs(w)});
    if (!(largest > 0.0)) return glm::dquat(1.0, 0.0, 0.0, 0.0);
    return glm::normalize(glm::dquat(w / largest, x / largest, y / largest, z / largest));
}

/// A node `matrix` as TRS. glTF requires it affine and free of shear; any shear (which
/// `Transform` cannot hold) is dropped by the decomposition.
Result<Transform> decomposeMatrix(const std::vector<double>& values, const std::string& where) {
    glm::dmat4 m(1.0);
    if (auto st = readNodeArray<16>(values, where, glm::value_ptr(m)); !st) return st.error();
    if (m[0][3] != 0.0 || m[1][3] != 0.0 || m[2][3] != 0.0 || m[3][3] != 1.0) {
        return elementError(where, "must be affine (last row 0, 0, 0, 1)");
    }
    Transform t;
    glm::dvec3 skew;
    glm::dvec4 perspective;
    const bool ok = glm::decompose(m, t.scale, t.rotation, t.translation, skew, perspective);
    const glm::dvec4 q(t.rotation.x, t.rotation.y, t.rotation.z, t.rotation.w);
    const bool finite = allFinite(
        {t.scale.x, t.scale.y, t.scale.z, q.x, q.y, q.z, q.w, t.translation.x, t.translation.y, t.translation.z});
    if (!ok || !finite) {
        return elementError(where, "cannot be decomposed into translation, rotation and scale");
    }
    t.rotation = unitQuat(q.x, q.y, q.z, q.w);
    return t;
}

Result<Transform> nodeTransform(const tinygltf::Node& node, const std::string& where) {
    if (!node.matrix.empty()) return decomposeMatrix(node.matrix, where + ".matrix");
    Transform t;
    double rotation[4] = {0.0, 0.0, 0.0, 1.0};
    if (auto st = readNodeArray<3>(node.translation, where + ".translation", glm::value_ptr(t.translation)); !st) {
        return st.error();
    }
    if (auto st = readNodeArray<4>(node.rotation, where + ".rotation", rotation); !st) {
        return st.error();
    }
    if (auto st = readNodeArray<3>(node.scale, where + ".scale", glm::value_ptr(t.scale)); !st) {
        return st.error();
    }
    t.rotation = unitQuat(rotation[0], rotation[1], rotation[2], rotation[3]);
    return t;
}

/// Checks an optional index of a node into one of the model's arrays.
Status checkReference(int index, std::size_t size, const std::string& where, const char* what) {
    if (index < -1 || (index >= 0 && static_cast<std::size_t>(index) >= size)) {
        return elementError(where, std::string(what) + " " + std::to_string(index) + " does not exist");
    }
    return Ok{};
}

/// What the importer needs of a node, checked.
struct NodeInfo {
    Transform transform;
    std::optional<std::size_t> light;
};

Result<NodeInfo> checkNode(const tinygltf::Model& model, std::size_t i, std::size_t lightCount) {
    const tinygltf::Node& node = model.nodes[i];
    const std::string where = indexed("nodes", i);
    if (auto st = checkReference(node.mesh, model.meshes.size(), where + ".mesh", "mesh"); !st) {
        return st.error();
    }
    if (auto st = checkReference(node.camera, model.cameras.size(), where + ".camera", "camera"); !st) {
        return st.error();
    }
    NodeInfo info;
    auto transform = nodeTransform(node, where);
    if (!transform) return transform.error();
    info.transform = *transform;
    auto light = gltf::nodeLight(node, i, lightCount);
    if (!light) return light.error();
    info.light = *light;
    return info;
}

/// Each node's parent (-1 for roots). The node graph must be a forest: children in range, no
/// node with two parents, no cycles.
Result<std::vector<int>> nodeParents(const tinygltf::Model& model) {
    const std::size_t n = model.nodes.size();
    std::vector<int> parents(n, -1);
    for (std::size_t i = 0; i < n; ++i) {
        const std::string where = indexed("nodes", i) + ".children";
        for (const int child : model.nodes[i].children) {
            if (child < 0 || static_cast<std::size_t>(child) >= n) {
                return elementError(where, "node " + std::to_string(child) + " does not exist");
            }
            int& parent = parents[static_cast<std::size_t>(child)];
            if (parent != -1) {
                return elementError(
                    indexed("nodes", static_cast<std::size_t>(child)),
                    "has two parents, nodes[" + std::to_string(parent) + "] and nodes[" + std::to_string(i) + "]");
            }
            parent = static_cast<int>(i);
        }
    }
    // With one parent per node, a cycle is a parent chain that never reaches a root. Walk up
    // from every node, marking the chain, in linear time overall.
    enum : unsigned char { kUnseen, kOnChain, kDone };
    std::vector<unsigned char> state(n, kUnseen);
    std::vector<std::size_t> chain;
    for (std::size_t start = 0; start < n; ++start) {
        chain.clear();
        int j = static_cast<int>(start);
        while (j != -1 && state[static_cast<std::size_t>(j)] == kUnseen) {
            state[static_cast<std::size_t>(j)] = kOnChain;
            chain.push_back(static_cast<std::size_t>(j));
            j = parents[static_cast<std::size_t>(j)];
        }
        if (j != -1 && state[static_cast<std::size_t>(j)] == kOnChain) {
            return elementError(indexed("nodes", static_cast<std::size_t>(j)), "is part of a cycle in the node graph");
        }
        for (const std::size_t k : chain) state[k] = kDone;
    }
    return parents;
}

/// The root nodes to instantiate, in order.
Result<std::vector<int>> sceneRoots(const tinygltf::Model& model, const std::vector<int>& parents) {
    std::vector<int> roots;
    if (model.scenes.empty()) {
        for (std::size_t i = 0; i < parents.size(); ++i) {
            if (parents[i] == -1) roots.push_back(static_cast<int>(i));
        }
        return roots;
    }
    const int chosen = model.defaultScene >= 0 ? model.defaultScene : 0;
    if (static_cast<std::size_t>(chosen) >= model.scenes.size()) {
        return elementError("scene", "scene " + std::to_string(chosen) + " does not exist");
    }
    const std::string where = indexed("scenes", static_cast<std::size_t>(chosen)) + ".nodes";
    std::vector<bool> listed(parents.size(), false);
    for (const int root : model.scenes[static_cast<std::size_t>(chosen)].nodes) {
        if (root < 0 || static_cast<std::size_t>(root) >= parents.size()) {
            return elementError(where, "node " + std::to_string(root) + " does not exist");
        }
        const auto r = static_cast<std::size_t>(root);
        if (parents[r] != -1) {
            return elementError(where, indexed("nodes", r) + " is not a root node");
        }
        if (listed[r]) return elementError(where, indexed("nodes", r) + " is listed twice");
        listed[r] = true;
        roots.push_back(root);
    }
    return roots;
}

// ---- cameras ----------------------------------------------------------------------------

/// Far plane used for glTF's infinite projection (no `zfar`): 10 km.
constexpr double kInfiniteFar = 1e4;

Result<Camera> importCamera(const tinygltf::Model& model, std::size_t index) {
    const tinygltf::Camera& camera = model.cameras[index];
    const std::string where = indexed("cameras", index);
    if (camera.type == "orthographic") {
        return elementError(where, "orthographic cameras are not supported");
    }
    if (camera.type != "perspective") {
        return elementError(where + ".type", "unknown camera type \"" + camera.type + "\"");
    }
    const tinygltf::PerspectiveCamera& p = camera.perspective;
    const std::string pw = where + ".perspective";
    if (!(p.yfov > 0.0 && p.yfov < glm::pi<double>())) {
        return elementError(pw + ".yfov", "must be in (0, pi)");
    }
    if (!(p.znear > 0.0 && std::isfinite(p.znear))) {
        return elementError(pw + ".znear", "must be a positive number");
    }
    const double zfar = p.zfar == 0.0 ? kInfiniteFar : p.zfar;
    if (!(zfar > p.znear && std::isfinite(zfar))) {
        return elementError(pw + ".zfar",
                            p.zfar == 0.0 ? "absent, and znear is beyond 1e4 m" : "must be greater than znear");
    }
    if (!(p.aspectRatio >= 0.0 && std::isfinite(p.aspectRatio))) {
        return elementError(pw + ".aspectRatio", "must be a positive number");
    }
    return Camera{static_cast<float>(p.yfov), static_cast<float>(p.znear), static_cast<float>(zfar),
                  static_cast<float>(p.aspectRatio)};
}

// ---- instantiation ----------------------------------------------------------------------

/// State of one import: the model, its checked parts, and the scene being built.
struct Importer {
    const tinygltf::Model& model;
    const GltfLoadOptions& options;
    std::vector<NodeInfo> nodes;
    std::vector<gltf::LightDefinition> lights;
    std::vector<Animation> animations;
    std::vector<std::optional<std::vector<gltf::MeshPart>>> meshes;  // built on first use
    Scene scene;

    Result<Entity> createEntity(const std::string& name, const Transform& transform) {
        // World::create asserts when out of slots; a file must not be able to trigger that.
        if (scene.world.size() + 1 >= Entity::kMaxEntities) {
            return Error{"too many nodes: the engine holds at most " + std::to_string(Entity::kMaxEntities - 1) +
                         " entities"};
        }
        const Entity e = scene.world.create();
        scene.world.emplace<Name>(e, Name{name});
        scene.world.emplace<Transform>(e, transform);
        return e;
    }

    Result<const std::vector<gltf::MeshPart>*> meshParts(std::size_t index) {
        if (!meshes[index]) {
            auto parts = gltf::importMesh(model, index);
            if (!parts) return parts.error();
            meshes[index] = std::move(*parts);
        }
        return &*meshes[index];
    }

    Status addMesh(std::size_t nodeIndex, Entity e, const std::string& name) {
        const tinygltf::Node& node = model.nodes[nodeIndex];
        auto parts = meshParts(static_cast<std::size_t>(node.mesh));
        if (!parts) return parts.error();
        const std::string where = indexed("nodes", nodeIndex);
        auto flags = gltf::orDefaults(gltf::parseMeshShadowExtras(node.extras, where), options.strictShadowSettings,
                                      where, scene.warnings);
        if (!flags) return flags.error();
        const auto attach = [&](Entity target, const gltf::MeshPart& part) {
            scene.world.emplace<Mesh>(target, Mesh{part.data, flags->cast, flags->receive});
            scene.world.emplace<Material>(target, part.material);
        };
        if ((*parts)->size() == 1) {
            attach(e, (**parts)[0]);
            return Ok{};
        }
        for (std::size_t k = 0; k < (*parts)->size(); ++k) {
            Transform local;
            local.parent = e;
            auto child = createEntity(name + "/primitive" + std::to_string(k), local);
            if (!child) return child.error();
            attach(*child, (**parts)[k]);
        }
        return Ok{};
    }

    void addLight(std::size_t lightIndex, Entity e) {
        const gltf::LightDefinition& def = lights[lightIndex];
        scene.world.emplace<Light>(e, def.light);
        if (def.shadow) scene.world.emplace<Shadow>(e, *def.shadow);
        scene.lights.push_back(e);
    }

    Result<Entity> instantiate(std::size_t i, Entity parent) {
        const tinygltf::Node& node = model.nodes[i];
        const std::string name = node.name.empty() ? "node" + std::to_string(i) : node.name;
        Transform transform = nodes[i].transform;
        transform.parent = parent;
        auto e = createEntity(name, transform);
        if (!e) return e.error();
        if (node.camera >= 0) {
            auto camera = importCamera(model, static_cast<std::size_t>(node.camera));
            if (!camera) return camera.error();
            scene.world.emplace<Camera>(*e, *camera);
            scene.cameras.push_back(*e);
        }
        if (nodes[i].light) addLight(*nodes[i].light, *e);
        if (node.mesh >= 0) {
            if (auto st = addMesh(i, *e, name); !st) return st.error();
        }
        if (!animations[i].channels.empty()) {
            scene.animationDuration = std::max(scene.animationDuration, animations[i].duration);
            scene.world.emplace<Animation>(*e, animations[i]);
        }
        return e;
    }

    /// Depth-first, pre-order, without recursion (node chains may be deep).
    Status instantiateAll(const std::vector<int>& roots) {
        struct Pending {
            std::size_t node;
            Entity parent;
        };
        std::vector<Pending> stack;
        for (auto it = roots.rbegin(); it != roots.rend(); ++it) {
            stack.push_back({static_cast<std::size_t>(*it), Entity::null()});
        }
        while (!stack.empty()) {
            const Pending next = stack.back();
            stack.pop_back();
            auto e = instantiate(next.node, next.parent);
            if (!e) return e.error();
            const std::vector<int>& children = model.nodes[next.node].children;
            for (auto it = children.rbegin(); it != children.rend(); ++it) {
                stack.push_back({static_cast<std::size_t>(*it), *e});
            }
        }
        return Ok{};
    }
};

/// Everything after parsing; errors and warnings carry the element but not yet the file name.
Result<Scene> buildScene(const tinygltf::Model& model, const std::string& name, const GltfLoadOptions& options) {
    Importer importer{model, options, {}, {}, {}, {}, {}};
    auto lights = gltf::importLights(model, options.strictShadowSettings, importer.scene.warnings);
    if (!lights) return lights.error();
    importer.lights = std::move(*lights);
    for (std::size_t i = 0; i < model.nodes.size(); ++i) {
        auto info = checkNode(model, i, importer.lights.size());
        if (!info) return info.error();
        importer.nodes.push_back(*info);
    }
    auto parents = nodeParents(model);
    if (!parents) return parents.error();
    auto roots = sceneRoots(model, *parents);
    if (!roots) return roots.error();
    auto animations = gltf::importAnimations(model);
    if (!animations) return animations.error();
    importer.animations = std::move(*animations);
    importer.meshes.resize(model.meshes.size());
    importer.scene.name = name;
    if (auto st = importer.instantiateAll(*roots); !st) return st.error();
    return std::move(importer.scene);
}

/// The scene of a parsed model; `source` (the file, or the in-memory name) prefixes every
/// error and warning message (a warning's element stays the glTF element alone).
Result<Scene> sceneOf(const tinygltf::Model& model, const std::string& source, const std::string& name,
                      const GltfLoadOptions& options) {
    auto scene = buildScene(model, name, options);
    if (!scene) return Error{source + ": " + scene.error().message};
    for (Warning& w : scene->warnings) w.message = source + ": " + w.message;
    return scene;
}

}  // namespace

Result<Scene> loadGltf(const std::string& path, const GltfLoadOptions& options) {
    auto model = readModel(path);
    if (!model) return model.error();
    return sceneOf(*model, path, std::filesystem::path(path).stem().string(), options);
}

namespace gltf {

Result<Scene> loadGltfFromMemory(std::string_view bytes, const std::string& name, const GltfLoadOptions& options) {
    const bool binary = bytes.size() >= 4 && bytes.substr(0, 4) == "glTF";
    // tinygltf takes the length as unsigned int.
    if (bytes.size() > std::numeric_limits<unsigned int>::max()) return Error{name + ": too large"};
    const auto* data = reinterpret_cast<const unsigned char*>(bytes.data());
    const auto size = static_cast<unsigned int>(bytes.size());
    auto model = parseModel(name, false,
                            [&](tinygltf::TinyGLTF& loader, tinygltf::Model& m, std::string& err, std::string& warn) {
                                return binary ? loader.LoadBinaryFromMemory(&m, &err, &warn, data, size, "")
                                              : loader.LoadASCIIFromString(&m, &err, &warn, bytes.data(), size, "");
                            });
    if (!model) return model.error();
    return sceneOf(*model, name, name, options);
}

}  // namespace gltf

}  // namespace shadow
