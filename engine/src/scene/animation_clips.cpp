// playAnimation: which of a loaded file's clips write the scene's `Animation` components.
//
// A glTF file's animations are alternatives more often than parts of one motion (a character's
// idle, walk and run), so one plays unless asked otherwise. Every clip stays in `Scene::clips`,
// so a game or the viewer switches without loading the file again.
#include <shadow/scene.h>

#include <algorithm>
#include <charconv>
#include <map>

namespace shadow {
namespace {

/// The clips `choice` names, or an error naming it and listing the scene's clips.
Result<std::vector<std::size_t>> chooseClips(const std::vector<AnimationClip>& clips, const std::string& choice) {
    std::vector<std::size_t> all(clips.size());
    for (std::size_t i = 0; i < clips.size(); ++i) all[i] = i;
    if (choice == "all") return all;
    if (choice.empty()) return clips.empty() ? std::vector<std::size_t>{} : std::vector<std::size_t>{0};
    std::size_t index = 0;
    const auto [end, ec] = std::from_chars(choice.data(), choice.data() + choice.size(), index);
    const bool digits = ec == std::errc{} && end == choice.data() + choice.size();
    if (digits && index < clips.size()) return std::vector<std::size_t>{index};
    if (!digits) {
        for (std::size_t i = 0; i < clips.size(); ++i) {
            if (clips[i].name == choice) return std::vector<std::size_t>{i};
        }
    }
    std::string known;
    for (std::size_t i = 0; i < clips.size(); ++i) {
        known += (i == 0 ? "" : ", ") + std::to_string(i) + " \"" + clips[i].name + "\"";
    }
    return Error{ErrorCode::InvalidArgument,
                 "animation \"" + choice + "\": " +
                     (clips.empty() ? std::string("the scene has no animations")
                                    : "no clip " + std::string(digits ? "of that index" : "of that name") +
                                          " (the scene's: " + known + ", or all)")};
}

}  // namespace

Status playAnimation(Scene& scene, const std::string& choice) {
    auto chosen = chooseClips(scene.clips, choice);
    if (!chosen) return chosen.error();
    if (scene.clips.empty()) return Ok{};  // a built-in scene's own animations stay as they are
    World& world = scene.world;
    // Every entity a clip moves back to its pose as loaded, without an animation...
    for (const AnimationClip& clip : scene.clips) {
        for (const AnimationClip::Target& target : clip.targets) {
            Transform* transform = world.tryGet<Transform>(target.entity);
            if (transform == nullptr) continue;  // destroyed by the game since
            transform->translation = target.rest.translation;
            transform->rotation = target.rest.rotation;
            transform->scale = target.rest.scale;
            if (Morph* morph = world.tryGet<Morph>(target.entity); morph != nullptr && !target.restWeights.empty()) {
                morph->weights = target.restWeights;
            }
            world.remove<Animation>(target.entity);
        }
    }
    // ... then the chosen clips' channels, in clip order.
    std::map<std::uint32_t, Animation> merged;  // by entity bits: one Animation per entity
    std::map<std::uint32_t, Entity> entities;
    scene.animationDuration = 0.0;
    for (const std::size_t c : *chosen) {
        const AnimationClip& clip = scene.clips[c];
        scene.animationDuration = std::max(scene.animationDuration, clip.duration);
        for (const AnimationClip::Target& target : clip.targets) {
            if (!world.alive(target.entity)) continue;
            Animation& animation = merged[target.entity.bits()];
            entities[target.entity.bits()] = target.entity;
            animation.channels.insert(animation.channels.end(), target.channels.begin(), target.channels.end());
            animation.duration = std::max(animation.duration, clip.duration);
        }
    }
    for (auto& [bits, animation] : merged) world.emplace<Animation>(entities[bits], std::move(animation));
    scene.playing = std::move(*chosen);
    return Ok{};
}

}  // namespace shadow
