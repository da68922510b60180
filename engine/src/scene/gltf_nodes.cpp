#include "scene/gltf_nodes.h"

#include <shadow/math.h>

#include <algorithm>
#include <cmath>
#include <glm/gtc/type_ptr.hpp>
#include <glm/gtx/matrix_decompose.hpp>
#include <initializer_list>

#include "scene/gltf_lights.h"
#include "scene/gltf_values.h"

namespace shadow::gltf {
namespace {

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

/// A singular node `matrix` with a zero column (a scale of 0) as TRS: the rotation from the
/// non-zero columns when two are left (the third axis follows, right-handed), else the identity
/// with `rotationUndetermined` set. The scale is each column's length, so the matrix is kept.
NodeInfo decomposeSingular(const glm::dmat4& m) {
    NodeInfo info;
    Transform& t = info.transform;
    t.translation = glm::dvec3(m[3]);
    glm::dvec3 axes[3];
    int nonZero = 0;
    for (int c = 0; c < 3; ++c) {
        axes[c] = glm::dvec3(m[c]);
        t.scale[c] = glm::length(axes[c]);
        if (t.scale[c] > 0.0) ++nonZero;
    }
    if (nonZero < 2) {
        info.rotationUndetermined = true;
        return info;
    }
    // Orthonormalise the two non-zero columns in order, then complete the right-handed frame.
    const int zero = t.scale.x == 0.0 ? 0 : (t.scale.y == 0.0 ? 1 : 2);
    const int a = (zero + 1) % 3;
    const int b = (zero + 2) % 3;
    const glm::dvec3 u = axes[a] / t.scale[a];
    const glm::dvec3 v = perpendicularPart(u, axes[b]);
    glm::dmat3 r;
    r[a] = u;
    r[b] = v;
    r[zero] = glm::cross(u, v);  // (a, b, zero) is a cyclic order of (x, y, z)
    t.rotation = glm::normalize(glm::quat_cast(r));
    return info;
}

/// A node `matrix` as TRS. glTF requires it affine and free of shear; any shear (which
/// `Transform` cannot hold) is dropped by the decomposition.
Result<NodeInfo> decomposeMatrix(const std::vector<double>& values, const std::string& where) {
    glm::dmat4 m(1.0);
    if (auto st = readNodeArray<16>(values, where, glm::value_ptr(m)); !st) return st.error();
    if (m[0][3] != 0.0 || m[1][3] != 0.0 || m[2][3] != 0.0 || m[3][3] != 1.0) {
        return elementError(where, "must be affine (last row 0, 0, 0, 1)");
    }
    // glm::decompose divides by each column's length.
    if (glm::dvec3(m[0]) == glm::dvec3(0.0) || glm::dvec3(m[1]) == glm::dvec3(0.0) ||
        glm::dvec3(m[2]) == glm::dvec3(0.0)) {
        return decomposeSingular(m);
    }
    NodeInfo info;
    Transform& t = info.transform;
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
    return info;
}

Result<NodeInfo> nodeTransform(const tinygltf::Node& node, const std::string& where) {
    if (!node.matrix.empty()) return decomposeMatrix(node.matrix, where + ".matrix");
    NodeInfo info;
    Transform& t = info.transform;
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
    return info;
}

/// Checks an optional index of a node into one of the model's arrays.
Status checkReference(int index, std::size_t size, const std::string& where, const char* what) {
    if (index < -1 || (index >= 0 && static_cast<std::size_t>(index) >= size)) {
        return elementError(where, std::string(what) + " " + std::to_string(index) + " does not exist");
    }
    return Ok{};
}

/// `nodes[i]` with its name, for messages: `nodes[3] ("arm")`.
std::string nodeLabel(const tinygltf::Model& model, std::size_t i) {
    const std::string& name = model.nodes[i].name;
    return indexed("nodes", i) + (name.empty() ? "" : " (\"" + name + "\")");
}

/// For every node, its nearest strict ancestor that `listed` marks, or -1. Each parent chain is
/// walked once (the answers are kept), so a deep graph costs linear time.
std::vector<int> listedAncestors(const std::vector<int>& parents, const std::vector<bool>& listed) {
    constexpr int kUnknown = -2;
    std::vector<int> holder(parents.size(), kUnknown);
    std::vector<std::size_t> chain;
    for (std::size_t start = 0; start < parents.size(); ++start) {
        chain.clear();
        std::size_t n = start;
        int answer = -1;
        while (holder[n] == kUnknown) {
            chain.push_back(n);
            const int p = parents[n];
            if (p == -1) break;
            if (listed[static_cast<std::size_t>(p)]) {
                answer = p;
                break;
            }
            n = static_cast<std::size_t>(p);
        }
        if (holder[n] != kUnknown) answer = holder[n];
        for (const std::size_t k : chain) holder[k] = answer;
    }
    return holder;
}

}  // namespace

Result<NodeInfo> checkNode(const tinygltf::Model& model, std::size_t i, std::size_t lightCount) {
    const tinygltf::Node& node = model.nodes[i];
    const std::string where = indexed("nodes", i);
    if (auto st = checkReference(node.mesh, model.meshes.size(), where + ".mesh", "mesh"); !st) {
        return st.error();
    }
    if (auto st = checkReference(node.camera, model.cameras.size(), where + ".camera", "camera"); !st) {
        return st.error();
    }
    auto transform = nodeTransform(node, where);
    if (!transform) return transform.error();
    NodeInfo info = *transform;
    auto light = gltf::nodeLight(node, i, lightCount);
    if (!light) return light.error();
    info.light = *light;
    return info;
}

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

Result<std::vector<int>> sceneRoots(const tinygltf::Model& model, const std::vector<int>& parents,
                                    std::vector<Warning>& warnings) {
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
    std::vector<int> unique;
    for (const int node : model.scenes[static_cast<std::size_t>(chosen)].nodes) {
        if (node < 0 || static_cast<std::size_t>(node) >= parents.size()) {
            return elementError(where, "node " + std::to_string(node) + " does not exist");
        }
        const auto n = static_cast<std::size_t>(node);
        if (listed[n]) {
            warnings.push_back({WarningCode::SceneNodeNotRoot, indexed("nodes", n),
                                where + " lists " + nodeLabel(model, n) + " twice; it is taken once"});
            continue;
        }
        listed[n] = true;
        unique.push_back(node);
    }
    const std::vector<int> holder = listedAncestors(parents, listed);
    for (const int node : unique) {
        const auto n = static_cast<std::size_t>(node);
        if (parents[n] == -1) {
            roots.push_back(node);
            continue;
        }
        std::string message = where + " lists " + nodeLabel(model, n) + ", which is not a root node (its parent is " +
                              indexed("nodes", static_cast<std::size_t>(parents[n])) + "); ";
        if (holder[n] >= 0) {
            message += "it is taken once, below " + indexed("nodes", static_cast<std::size_t>(holder[n])) +
                       ", which the scene holds too";
        } else {
            message +=
                "it is taken as a root of its own subtree, with its own transform (its ancestors are in no "
                "subtree the scene lists)";
            roots.push_back(node);
        }
        warnings.push_back({WarningCode::SceneNodeNotRoot, indexed("nodes", n), std::move(message)});
    }
    return roots;
}

}  // namespace shadow::gltf
