#include "scene/gltf_animation.h"

#include <algorithm>
#include <optional>

#include "scene/gltf_accessors.h"
#include "scene/gltf_values.h"

namespace shadow::gltf {
namespace {

using Interpolation = AnimationChannel::Interpolation;
using Path = AnimationChannel::Path;

std::optional<Path> parsePath(const std::string& path) {
    if (path == "translation") return Path::Translation;
    if (path == "rotation") return Path::Rotation;
    if (path == "scale") return Path::Scale;
    if (path == "weights") return Path::Weights;
    return std::nullopt;
}

Result<Interpolation> parseInterpolation(const std::string& name, const std::string& where) {
    if (name == "LINEAR") return Interpolation::Linear;
    if (name == "STEP") return Interpolation::Step;
    if (name == "CUBICSPLINE") return Interpolation::CubicSpline;
    return elementError(where + ".interpolation", "unknown interpolation \"" + name + "\"");
}

Result<std::vector<float>> readKeyTimes(const tinygltf::Model& model, int accessor, const std::string& where) {
    auto times = readScalars(model, accessor, where);
    if (!times) return times.error();
    if (times->empty()) return elementError(where, "has no keys");
    for (std::size_t k = 1; k < times->size(); ++k) {
        if (!((*times)[k] > (*times)[k - 1])) {
            return elementError(where, "key times not strictly increasing at key " + std::to_string(k));
        }
    }
    return times;
}

/// Morph weights, `targets` per value, packed four to a vec4 (`AnimationChannel::width` each).
Result<std::vector<glm::vec4>> readWeightValues(const tinygltf::Model& model, int accessor, std::size_t targets,
                                                const std::string& where) {
    auto scalars = readScalars(model, accessor, where);
    if (!scalars) return scalars.error();
    if (scalars->size() % targets != 0) {
        return elementError(where, "has " + std::to_string(scalars->size()) + " weights, not a multiple of the " +
                                       std::to_string(targets) + " morph targets");
    }
    const std::size_t width = (targets + 3) / 4;
    std::vector<glm::vec4> out(scalars->size() / targets * width, glm::vec4(0.0f));
    for (std::size_t i = 0; i < scalars->size(); ++i) {
        const std::size_t value = i / targets, k = i % targets;
        out[value * width + k / 4][static_cast<int>(k % 4)] = (*scalars)[i];
    }
    return out;
}

/// Output values as vec4 (xyz keys get w = 0; weights packed, see readWeightValues).
Result<std::vector<glm::vec4>> readKeyValues(const tinygltf::Model& model, int accessor, Path path, std::size_t targets,
                                             const std::string& where) {
    if (path == Path::Rotation) return readRotations(model, accessor, where);
    if (path == Path::Weights) return readWeightValues(model, accessor, targets, where);
    auto xyz = readVec3(model, accessor, where);
    if (!xyz) return xyz.error();
    std::vector<glm::vec4> out(xyz->size());
    for (std::size_t i = 0; i < out.size(); ++i) out[i] = glm::vec4((*xyz)[i], 0.0f);
    return out;
}

/// `targets`: the morph targets a `weights` channel's node has (0 for other paths).
Result<AnimationChannel> importSampler(const tinygltf::Model& model, const tinygltf::AnimationSampler& sampler,
                                       Path path, std::size_t targets, const std::string& where) {
    AnimationChannel channel;
    channel.path = path;
    channel.width = path == Path::Weights ? static_cast<std::uint32_t>((targets + 3) / 4) : 1;
    auto interpolation = parseInterpolation(sampler.interpolation, where);
    if (!interpolation) return interpolation.error();
    channel.interpolation = *interpolation;
    auto times = readKeyTimes(model, sampler.input, where + ".input");
    if (!times) return times.error();
    channel.times = std::move(*times);
    auto values = readKeyValues(model, sampler.output, path, targets, where + ".output");
    if (!values) return values.error();
    channel.values = std::move(*values);
    const std::size_t perKey = channel.interpolation == Interpolation::CubicSpline ? 3 : 1;
    const std::size_t count = channel.values.size() / channel.width;
    if (count != perKey * channel.times.size()) {
        return elementError(where + ".output", "has " + std::to_string(count) + " values for " +
                                                   std::to_string(channel.times.size()) + " keys (expected " +
                                                   std::to_string(perKey * channel.times.size()) + ")");
    }
    return channel;
}

/// The morph targets of `nodes[node]`'s mesh (glTF: every primitive has as many); 0 without.
std::size_t morphTargetsOf(const tinygltf::Model& model, int node) {
    const int mesh = model.nodes[static_cast<std::size_t>(node)].mesh;
    if (mesh < 0 || static_cast<std::size_t>(mesh) >= model.meshes.size()) return 0;
    const auto& primitives = model.meshes[static_cast<std::size_t>(mesh)].primitives;
    return primitives.empty() ? 0 : primitives.front().targets.size();
}

/// The usable channels of `animations[index]`.
Result<ImportedClip> importAnimation(const tinygltf::Model& model, std::size_t index) {
    const tinygltf::Animation& animation = model.animations[index];
    const std::string where = indexed("animations", index);
    ImportedClip out;
    out.name = animation.name.empty() ? "animation" + std::to_string(index) : animation.name;
    for (std::size_t c = 0; c < animation.channels.size(); ++c) {
        const tinygltf::AnimationChannel& channel = animation.channels[c];
        const std::string channelWhere = where + "." + indexed("channels", c);
        const std::optional<Path> path = parsePath(channel.target_path);
        if (!path) continue;
        if (channel.sampler < 0 || static_cast<std::size_t>(channel.sampler) >= animation.samplers.size()) {
            return elementError(channelWhere + ".sampler",
                                "sampler " + std::to_string(channel.sampler) + " does not exist");
        }
        if (channel.target_node < 0 || static_cast<std::size_t>(channel.target_node) >= model.nodes.size()) {
            return elementError(channelWhere + ".target.node",
                                "node " + std::to_string(channel.target_node) + " does not exist");
        }
        const std::size_t targets = *path == Path::Weights ? morphTargetsOf(model, channel.target_node) : 0;
        if (*path == Path::Weights && targets == 0) {
            return elementError(channelWhere + ".target.node", "node " + std::to_string(channel.target_node) +
                                                                   " has no mesh with morph targets for its weights");
        }
        const auto samplerIndex = static_cast<std::size_t>(channel.sampler);
        auto sampled = importSampler(model, animation.samplers[samplerIndex], *path, targets,
                                     where + "." + indexed("samplers", samplerIndex));
        if (!sampled) return sampled.error();
        out.duration = std::max(out.duration, static_cast<double>(sampled->times.back()));
        out.channels.emplace_back(static_cast<std::size_t>(channel.target_node), std::move(*sampled));
    }
    return out;
}

}  // namespace

Result<std::vector<ImportedClip>> importAnimations(const tinygltf::Model& model) {
    std::vector<ImportedClip> clips;
    for (std::size_t a = 0; a < model.animations.size(); ++a) {
        auto clip = importAnimation(model, a);
        if (!clip) return clip.error();
        clips.push_back(std::move(*clip));
    }
    return clips;
}

}  // namespace shadow::gltf
