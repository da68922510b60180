// loadGltf: a glTF 2.0 file (.gltf with embedded or external buffers, or .glb) to a Scene.
//
// tinygltf parses the JSON and the GLB container; everything it does not check is checked
// here before use (accessor ranges, index values, finiteness, node graph shape, index
// references), and every problem is an `Error` of the form `<file>: <element>: <problem>`.
//
// Entities: one per node of the chosen scene (the file's `scene`, else scenes[0], else every
// root node in index order; a listed node that is not a root is taken once, see sceneRoots).
// Nodes are visited depth-first, pre-order: the scene's roots in
// the order the scene lists them, each node's children in the order of its `children` array.
// `Scene::lights` and `Scene::cameras` are in that visiting order (so `visibility_<i>.exr`
// numbers light instances in it). Nodes outside the chosen scene are validated but not
// instantiated.
//
// A mesh node whose mesh has one drawable primitive carries `Mesh` and `Material` itself;
// with several, each primitive becomes a child entity `<node>/primitive<k>`. Instances of one
// glTF mesh share its `MeshData`.
//
// Materials keep their base-colour texture (decoded when a material uses it, gltf_textures)
// and alpha mode; skins become a `Skin` on the mesh's entities, its joints the entities of the
// joint nodes (posed by `updateTransforms`).
//
// The file's animations become `Scene::clips`; the one `GltfLoadOptions::animation` names plays
// (animation_clips.cpp). Morph targets become a `Morph` on the mesh's entities (weights: the node's, else
// the mesh's), which `weights` channels animate. What the module leaves out (vertex colours,
// material extensions, ...) is one warning per kind, from the one table of
// gltf_support.cpp; orthographic cameras are an error when a node uses one.
//
// Each step lives in a file of its topic: gltf_parse (bytes to a tinygltf model, with
// gltf_schema's member types and gltf_support's extensions checked), gltf_nodes
// (transforms, references, the node graph), gltf_cameras, gltf_lights, gltf_mesh (with
// gltf_accessors), gltf_animation, gltf_values (typed JSON reads). This file instantiates.
#include "scene/gltf_import.h"

#include <shadow/scene.h>
#include <tiny_gltf.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string_view>

#include "scene/gltf_accessors.h"
#include "scene/gltf_animation.h"
#include "scene/gltf_cameras.h"
#include "scene/gltf_lights.h"
#include "scene/gltf_mesh.h"
#include "scene/gltf_nodes.h"
#include "scene/gltf_parse.h"
#include "scene/gltf_values.h"
#include "scene/shadow_extras.h"

namespace shadow {
namespace {

using gltf::indexed;

/// State of one import: the model, its checked parts, and the scene being built.
struct Importer {
    const tinygltf::Model& model;
    const GltfLoadOptions& options;
    std::vector<gltf::NodeInfo> nodes;
    std::vector<gltf::LightDefinition> lights;
    std::vector<gltf::ImportedClip> clips;
    std::vector<std::optional<std::vector<gltf::MeshPart>>> meshes;  // built on first use
    Scene scene;
    gltf::TextureImporter textures{model, scene.warnings};
    std::vector<Entity> entityOfNode;  ///< null for nodes outside the chosen scene
    /// Entities carrying a mesh of a skinned node, with that node: skinned once every node is.
    std::vector<std::pair<Entity, std::size_t>> skinned;
    /// Per node, the entities carrying its mesh's primitives when they have morph targets: what
    /// the node's `weights` channels animate.
    std::vector<std::vector<Entity>> morphedOfNode;

    Importer(const tinygltf::Model& m, const GltfLoadOptions& o) : model(m), options(o) {}

    Result<Entity> createEntity(const std::string& name, const Transform& transform) {
        // World::create asserts when out of slots; a file must not be able to trigger that.
        if (scene.world.size() + 1 >= Entity::kMaxEntities) {
            return Error{ErrorCode::LimitExceeded, "too many nodes: the engine holds at most " +
                                                       std::to_string(Entity::kMaxEntities - 1) + " entities"};
        }
        const Entity e = scene.world.create();
        scene.world.emplace<Name>(e, Name{name});
        scene.world.emplace<Transform>(e, transform);
        return e;
    }

    Result<const std::vector<gltf::MeshPart>*> meshParts(std::size_t index) {
        if (!meshes[index]) {
            auto parts = gltf::importMesh(model, index, textures, scene.warnings);
            if (!parts) return parts.error();
            meshes[index] = std::move(*parts);
        }
        return &*meshes[index];
    }

    /// The morph weights of `nodes[nodeIndex]`'s mesh, whose primitives have `targets` each: the
    /// node's `weights`, else the mesh's, else zeros; each list one finite number per target.
    Result<std::vector<float>> morphWeights(std::size_t nodeIndex, std::size_t targets) const {
        const tinygltf::Node& node = model.nodes[nodeIndex];
        const auto meshIndex = static_cast<std::size_t>(node.mesh);
        const bool own = !node.weights.empty();
        const std::vector<double>& weights = own ? node.weights : model.meshes[meshIndex].weights;
        if (weights.empty()) return std::vector<float>(targets, 0.0f);
        const std::string where = (own ? indexed("nodes", nodeIndex) : indexed("meshes", meshIndex)) + ".weights";
        if (weights.size() != targets) {
            return gltf::elementError(where, "has " + std::to_string(weights.size()) + " weights for " +
                                                 std::to_string(targets) + " morph targets");
        }
        std::vector<float> out;
        for (const double w : weights) {
            if (!std::isfinite(static_cast<float>(w)))
                return gltf::elementError(where, "has a weight that is not finite");
            out.push_back(static_cast<float>(w));
        }
        return out;
    }

    Status addMesh(std::size_t nodeIndex, Entity e, const std::string& name) {
        const tinygltf::Node& node = model.nodes[nodeIndex];
        auto parts = meshParts(static_cast<std::size_t>(node.mesh));
        if (!parts) return parts.error();
        const std::string where = indexed("nodes", nodeIndex);
        auto flags = gltf::orDefaults(gltf::parseMeshShadowExtras(node.extras, where), options.strictShadowSettings,
                                      where, scene.warnings);
        if (!flags) return flags.error();
        gltf::warnUnknownShadowKeys(node.extras, where, /*light=*/false, scene.warnings);
        const std::size_t targets = (*parts)->empty() ? 0 : (*parts)->front().data->morphTargets;
        std::vector<float> weights;
        if (targets > 0) {
            auto w = morphWeights(nodeIndex, targets);
            if (!w) return w.error();
            weights = std::move(*w);
        }
        const auto attach = [&](Entity target, const gltf::MeshPart& part) {
            scene.world.emplace<Mesh>(target, Mesh{part.data, flags->cast, flags->receive});
            scene.world.emplace<Material>(target, part.material);
            if (node.skin >= 0) skinned.emplace_back(target, nodeIndex);
            if (targets > 0) {
                scene.world.emplace<Morph>(target, Morph{weights, {}, false, false});
                morphedOfNode[nodeIndex].push_back(target);
            }
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
        if (!def.supported) return;
        scene.world.emplace<Light>(e, def.light);
        if (def.shadow) scene.world.emplace<Shadow>(e, *def.shadow);
        scene.lights.push_back(e);
    }

    /// Warns that the light or camera of `nodes[i]` points down the default axes: `nodes[from]`
    /// (itself or an ancestor) has a `matrix` without a rotation.
    void warnUndeterminedRotation(std::size_t i, std::size_t from, const std::string& name) {
        const std::string where = indexed("nodes", i);
        std::string message = where + " (" + name + "): ";
        message += from == i ? "its matrix" : "the matrix of its ancestor " + indexed("nodes", from);
        message +=
            " has fewer than two non-zero columns and so no rotation; the identity was taken "
            "(-Z forward, +Y up in the parent's frame)";
        scene.warnings.push_back({WarningCode::DegenerateTransform, where, std::move(message)});
    }

    /// `undeterminedFrom`: the nearest node, this one or an ancestor, whose matrix holds no
    /// rotation.
    Result<Entity> instantiate(std::size_t i, Entity parent, std::optional<std::size_t> undeterminedFrom) {
        const tinygltf::Node& node = model.nodes[i];
        const std::string name = node.name.empty() ? "node" + std::to_string(i) : node.name;
        const bool hasLight = nodes[i].light && lights[*nodes[i].light].supported;
        if (undeterminedFrom && (node.camera >= 0 || hasLight)) warnUndeterminedRotation(i, *undeterminedFrom, name);
        Transform transform = nodes[i].transform;
        transform.parent = parent;
        auto e = createEntity(name, transform);
        if (!e) return e.error();
        entityOfNode[i] = *e;
        if (node.camera >= 0) {
            auto camera = gltf::importCamera(model, static_cast<std::size_t>(node.camera));
            if (!camera) return camera.error();
            scene.world.emplace<Camera>(*e, *camera);
            scene.cameras.push_back(*e);
        }
        if (nodes[i].light) addLight(*nodes[i].light, *e);
        if (node.mesh >= 0) {
            if (auto st = addMesh(i, *e, name); !st) return st.error();
        }
        return e;
    }

    /// The `Skin` of `nodes[nodeIndex]` (which has one), for `target`, one of its mesh entities.
    Status addSkin(Entity target, std::size_t nodeIndex) {
        const auto skinIndex = static_cast<std::size_t>(model.nodes[nodeIndex].skin);
        const std::string where = indexed("nodes", nodeIndex) + ".skin";
        if (skinIndex >= model.skins.size()) {
            return gltf::elementError(where, "skin " + std::to_string(skinIndex) + " does not exist");
        }
        const tinygltf::Skin& source = model.skins[skinIndex];
        const std::string skinWhere = indexed("skins", skinIndex);
        if (source.joints.empty()) return gltf::elementError(skinWhere + ".joints", "is empty");
        Skin skin;
        for (const int joint : source.joints) {
            if (joint < 0 || static_cast<std::size_t>(joint) >= entityOfNode.size() ||
                entityOfNode[static_cast<std::size_t>(joint)].isNull()) {
                return gltf::elementError(skinWhere + ".joints",
                                          "node " + std::to_string(joint) + " is not a node of the scene");
            }
            skin.joints.push_back(entityOfNode[static_cast<std::size_t>(joint)]);
        }
        skin.inverseBind.assign(skin.joints.size(), glm::dmat4(1.0));
        if (source.inverseBindMatrices >= 0) {
            auto matrices = gltf::readMat4(model, source.inverseBindMatrices, skinWhere + ".inverseBindMatrices");
            if (!matrices) return matrices.error();
            if (matrices->size() < skin.joints.size()) {
                return gltf::elementError(skinWhere + ".inverseBindMatrices",
                                          "has " + std::to_string(matrices->size()) + " matrices for " +
                                              std::to_string(skin.joints.size()) + " joints");
            }
            std::copy_n(matrices->begin(), skin.joints.size(), skin.inverseBind.begin());
        }
        const MeshData& data = *scene.world.get<Mesh>(target).data;
        if (data.joints.empty()) {
            return gltf::elementError(where, "is set, but mesh \"" + data.name + "\" has no JOINTS_0/WEIGHTS_0");
        }
        if (data.jointBounds.size() > skin.joints.size()) {
            return gltf::elementError(where, "mesh \"" + data.name + "\" weights joint " +
                                                 std::to_string(data.jointBounds.size() - 1) + " of a skin with " +
                                                 std::to_string(skin.joints.size()));
        }
        scene.world.emplace<Skin>(target, std::move(skin));
        return Ok{};
    }

    /// `Scene::clips` from the file's animations: channels of nodes outside the chosen scene
    /// are left out, each entity's channels of one clip kept together.
    void addClips() {
        for (gltf::ImportedClip& imported : clips) {
            AnimationClip& clip = scene.clips.emplace_back();
            clip.name = std::move(imported.name);
            clip.duration = imported.duration;
            std::map<std::uint32_t, std::size_t> targetOf;  // by entity bits
            const auto add = [&](Entity e, const AnimationChannel& channel) {
                const auto [it, added] = targetOf.emplace(e.bits(), clip.targets.size());
                if (added) {
                    const Morph* morph = scene.world.tryGet<Morph>(e);
                    clip.targets.push_back({e,
                                            {},
                                            scene.world.get<Transform>(e),
                                            morph != nullptr ? morph->weights : std::vector<float>{}});
                }
                clip.targets[it->second].channels.push_back(channel);
            };
            for (auto& [node, channel] : imported.channels) {
                if (entityOfNode[node].isNull()) continue;
                if (channel.path != AnimationChannel::Path::Weights) {
                    add(entityOfNode[node], channel);
                    continue;
                }
                // A node's weights morph each primitive of its mesh (one entity, or one per primitive).
                for (const Entity e : morphedOfNode[node]) add(e, channel);
            }
        }
    }

    Status addSkins() {
        for (const auto& [target, node] : skinned) {
            if (auto st = addSkin(target, node); !st) return st;
        }
        return Ok{};
    }

    /// Depth-first, pre-order, without recursion (node chains may be deep).
    Status instantiateAll(const std::vector<int>& roots) {
        struct Pending {
            std::size_t node;
            Entity parent;
            std::optional<std::size_t> undeterminedAbove;  // see instantiate
        };
        std::vector<Pending> stack;
        for (auto it = roots.rbegin(); it != roots.rend(); ++it) {
            stack.push_back({static_cast<std::size_t>(*it), Entity::null(), std::nullopt});
        }
        while (!stack.empty()) {
            const Pending next = stack.back();
            stack.pop_back();
            const std::optional<std::size_t> undetermined =
                nodes[next.node].rotationUndetermined ? std::optional<std::size_t>(next.node) : next.undeterminedAbove;
            auto e = instantiate(next.node, next.parent, undetermined);
            if (!e) return e.error();
            const std::vector<int>& children = model.nodes[next.node].children;
            for (auto it = children.rbegin(); it != children.rend(); ++it) {
                stack.push_back({static_cast<std::size_t>(*it), *e, undetermined});
            }
        }
        return Ok{};
    }
};

/// Everything after parsing; errors and warnings carry the element but not yet the file name.
Result<Scene> buildScene(const gltf::ParsedGltf& parsed, const std::string& name, const GltfLoadOptions& options) {
    const tinygltf::Model& model = parsed.model;
    Importer importer(model, options);
    importer.scene.warnings = parsed.warnings;
    auto lights = gltf::importLights(model, options.strictShadowSettings, importer.scene.warnings);
    if (!lights) return lights.error();
    importer.lights = std::move(*lights);
    for (std::size_t i = 0; i < model.nodes.size(); ++i) {
        auto info = gltf::checkNode(model, i, importer.lights.size());
        if (!info) return info.error();
        importer.nodes.push_back(*info);
    }
    auto parents = gltf::nodeParents(model);
    if (!parents) return parents.error();
    auto roots = gltf::sceneRoots(model, *parents, importer.scene.warnings);
    if (!roots) return roots.error();
    auto clips = gltf::importAnimations(model);
    if (!clips) return clips.error();
    importer.clips = std::move(*clips);
    importer.meshes.resize(model.meshes.size());
    importer.entityOfNode.assign(model.nodes.size(), Entity::null());
    importer.morphedOfNode.resize(model.nodes.size());
    importer.scene.name = name;
    if (auto st = importer.instantiateAll(*roots); !st) return st.error();
    if (auto st = importer.addSkins(); !st) return st.error();
    importer.addClips();
    if (auto st = playAnimation(importer.scene, options.animation); !st) return st.error();
    return std::move(importer.scene);
}

/// The scene of a parsed model; `source` (the file, or the in-memory name) prefixes every
/// error and warning message (a warning's element stays the glTF element alone).
Result<Scene> sceneOf(const gltf::ParsedGltf& parsed, const std::string& source, const std::string& name,
                      const GltfLoadOptions& options) {
    auto scene = buildScene(parsed, name, options);
    if (!scene) return scene.error().within(source + ": ");
    for (Warning& w : scene->warnings) w.message = source + ": " + w.message;
    return scene;
}

}  // namespace

Result<Scene> loadGltf(const std::string& path, const GltfLoadOptions& options) {
    auto model = gltf::readModel(path);
    if (!model) return model.error();
    return sceneOf(*model, path, std::filesystem::path(path).stem().string(), options);
}

namespace gltf {

Result<Scene> loadGltfFromMemory(std::string_view bytes, const std::string& name, const GltfLoadOptions& options) {
    auto model = readModelFromMemory(bytes, name);
    if (!model) return model.error();
    return sceneOf(*model, name, name, options);
}

}  // namespace gltf

}  // namespace shadow
