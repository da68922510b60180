#include "viewer_ui.h"

#include "viewer_script.h"
#include "viewer_settings.h"

#include <imgui.h>

#include <algorithm>
#include <cstdio>
#include <optional>
#include <string>

namespace shadow::viewer {
namespace {

const ImVec4 kWarningColour(1.0f, 0.75f, 0.3f, 1.0f);
const ImVec4 kErrorColour(1.0f, 0.4f, 0.4f, 1.0f);

/// The last frame, scaled to fit the window with its aspect kept, behind every panel.
void drawFrameBackground(const ViewerState& state) {
    if (!state.frameTexture || state.frameWidth < 1 || state.frameHeight < 1) return;
    const ImVec2 display = ImGui::GetIO().DisplaySize;
    const float scale =
        std::min(display.x / static_cast<float>(state.frameWidth), display.y / static_cast<float>(state.frameHeight));
    const ImVec2 size(scale * static_cast<float>(state.frameWidth), scale * static_cast<float>(state.frameHeight));
    const ImVec2 min(0.5f * (display.x - size.x), 0.5f * (display.y - size.y));
    ImGui::GetBackgroundDrawList()->AddImage(textureId(state.frameTexture), min,
                                             ImVec2(min.x + size.x, min.y + size.y));
}

std::string lightLabel(const ViewerState& state, int i) {
    const Entity e = state.scene.lights[static_cast<std::size_t>(i)];
    const Name* name = state.scene.world.tryGet<Name>(e);
    return std::to_string(i) + ": " + (name != nullptr ? name->value : "light");
}

/// A combo over the scene's lights; true when the choice changed.
bool lightCombo(const char* label, const ViewerState& state, int& light) {
    const int count = static_cast<int>(state.scene.lights.size());
    if (count == 0) return false;
    bool changed = false;
    if (ImGui::BeginCombo(label, lightLabel(state, std::clamp(light, 0, count - 1)).c_str())) {
        for (int i = 0; i < count; ++i) {
            if (ImGui::Selectable(lightLabel(state, i).c_str(), i == light)) {
                light = i;
                changed = true;
            }
        }
        ImGui::EndCombo();
    }
    return changed;
}

void drawCameraSection(ViewerState& state, UiRequests& requests) {
    CameraRig& rig = state.rig;
    int mode = static_cast<int>(rig.mode());
    ImGui::Text("Camera");
    ImGui::SameLine();
    bool changed = ImGui::RadioButton("scene", &mode, 0);
    ImGui::SameLine();
    changed |= ImGui::RadioButton("orbit", &mode, 1);
    ImGui::SameLine();
    changed |= ImGui::RadioButton("fly", &mode, 2);
    if (changed) {
        rig.setMode(state.scene.world, static_cast<CameraRig::Mode>(mode));
        state.dirty = true;
    }
    for (std::size_t i = 0; i < state.scene.cameras.size(); ++i) {
        if (i > 0) ImGui::SameLine();
        const std::string label = "camera " + std::to_string(i);
        if (ImGui::SmallButton(label.c_str())) requests.sceneCamera = static_cast<int>(i);
    }
    ImGui::TextDisabled(rig.mode() == CameraRig::Mode::Fly ? "drag: look, WASD/QE: move (%.2g m/s), Shift: faster"
                                                           : "drag: orbit, scroll/right-drag: zoom, middle-drag: pan",
                        rig.flySpeed());
}

/// The clip picker: one of the file's clips, or all of them at once.
void drawClipCombo(ViewerState& state) {
    const std::vector<AnimationClip>& clips = state.scene.clips;
    if (clips.empty()) return;
    const bool all = state.scene.playing.size() > 1;
    const std::size_t current = state.scene.playing.empty() ? 0 : state.scene.playing[0];
    const auto label = [&](std::size_t i) { return std::to_string(i) + ": " + clips[i].name; };
    if (!ImGui::BeginCombo("clip", all ? "all" : label(current).c_str())) return;
    std::optional<std::string> choice;
    for (std::size_t i = 0; i < clips.size(); ++i) {
        if (ImGui::Selectable(label(i).c_str(), !all && i == current)) choice = std::to_string(i);
    }
    if (ImGui::Selectable("all", all)) choice = "all";
    ImGui::EndCombo();
    if (!choice) return;
    // Indices and `all` come from the list above, so the choice is always there.
    if (Status s = playAnimation(state.scene, *choice); !s) state.status = s.error().message;
    state.animation = *choice;
    state.dirty = true;
}

/// For a file without lights: what lights it, and the switches of the default rig.
void drawDefaultRigSection(ViewerState& state, UiRequests& requests) {
    if (!state.defaultRigShown && !state.scene.lights.empty()) return;
    if (state.defaultRigShown) {
        ImGui::TextColored(kWarningColour, "This file has no lights: it is lit by the default rig,");
        ImGui::TextColored(kWarningColour, "a shadowed sun placed from the model's bounds%s.",
                           state.rigChoice.ground ? " and a ground" : "");
    } else {
        ImGui::TextColored(kWarningColour, "This file has no lights: ambient light only.");
    }
    requests.reload |= ImGui::Checkbox("default rig", &state.rigChoice.lights);
    if (state.rigChoice.lights) {
        ImGui::SameLine();
        requests.reload |= ImGui::Checkbox("ground", &state.rigChoice.ground);
    }
    ImGui::Separator();
}

void drawAnimationSection(ViewerState& state) {
    drawClipCombo(state);
    ImGui::Checkbox("paused (Space)", &state.paused);
    ImGui::SameLine();
    ImGui::SetNextItemWidth(120.0f);
    ImGui::SliderFloat("speed", &state.speed, 0.0f, 4.0f, "%.2fx");
    // Over the longest clip; a scene of procedural motion only has no length, so a minute.
    const double end = state.scene.animationDuration > 0.0 ? state.scene.animationDuration : 60.0;
    float t = static_cast<float>(std::fmod(state.time, end));
    if (ImGui::SliderFloat("time (s)", &t, 0.0f, static_cast<float>(end), "%.3f")) {
        state.time = t;
        state.paused = true;
        state.dirty = true;
    }
}

void drawViewSection(ViewerState& state) {
    ImGui::Checkbox("auto exposure", &state.autoExposure);
    ImGui::SameLine();
    ImGui::SetNextItemWidth(150.0f);
    if (ImGui::SliderFloat("exposure", &state.exposure, 0.01f, 100.0f, "%.3f", ImGuiSliderFlags_Logarithmic)) {
        state.autoExposure = false;
    }
    DebugView& view = state.options.debugView;
    if (ImGui::BeginCombo("debug view", debugViewName(view))) {
        for (DebugView v : debugViews()) {
            if (ImGui::Selectable(debugViewName(v), v == view)) {
                view = v;
                state.dirty = true;
            }
        }
        ImGui::EndCombo();
    }
    if (view != DebugView::None && lightCombo("debug light", state, state.options.debugLight)) state.dirty = true;
    ScreenVisibility& screen = state.options.screenVisibility;
    if (ImGui::BeginCombo("screen visibility", screenVisibilityName(screen))) {
        for (const ScreenVisibility v : {ScreenVisibility::Auto, ScreenVisibility::Off, ScreenVisibility::Full,
                                         ScreenVisibility::Half, ScreenVisibility::Quarter}) {
            if (ImGui::Selectable(screenVisibilityName(v), v == screen)) {
                screen = v;
                state.dirty = true;
            }
        }
        ImGui::EndCombo();
    }
    ShadowMapView& map = state.mapView;
    if (ImGui::Checkbox("show a shadow map", &map.shown)) map.stale = true;
    if (map.shown) {
        if (lightCombo("map light", state, map.light)) map.stale = true;
        const int layers = state.runner->shadows().maps().layersOf(static_cast<std::size_t>(map.light));
        if (layers > 1 && ImGui::SliderInt("layer", &map.layer, 0, layers - 1)) map.stale = true;
        map.layer = std::clamp(map.layer, 0, std::max(layers - 1, 0));
    }
}

void drawScenePanel(ViewerState& state, UiRequests& requests) {
    ImGui::SetNextWindowPos(ImVec2(10, 10), ImGuiCond_FirstUseEver);
    if (!ImGui::Begin("Scene", nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
        ImGui::End();
        return;
    }
    ImGui::TextWrapped("%s", state.sceneSpec.c_str());
    ImGui::TextDisabled("drop a .gltf/.glb on the window to load it");
    if (!state.loadError.empty()) ImGui::TextColored(kErrorColour, "%s", state.loadError.c_str());
    drawDefaultRigSection(state, requests);
    drawCameraSection(state, requests);
    ImGui::Separator();
    drawAnimationSection(state);
    ImGui::Separator();
    drawViewSection(state);
    if (ImGui::Button("screenshot (P)")) requests.screenshot = true;
    if (!state.status.empty()) ImGui::TextWrapped("%s", state.status.c_str());
    ImGui::End();
}

/// One widget for `setting` of `light`; writes the edit into the light's components.
void settingWidget(ViewerState& state, Entity light, const LightSetting& setting) {
    World& world = state.scene.world;
    const double value = readSetting(world, light, setting);
    bool changed = false;
    double edited = value;
    switch (setting.kind) {
        case LightSetting::Kind::Technique: {
            const auto current = static_cast<ShadowTechnique>(value);
            if (ImGui::BeginCombo(setting.label, techniqueName(current))) {
                for (int t = 0; t < kShadowTechniqueCount; ++t) {
                    const auto technique = static_cast<ShadowTechnique>(t);
                    if (!techniqueAvailable(technique)) continue;
                    if (ImGui::Selectable(techniqueName(technique), technique == current)) {
                        edited = t;
                        changed = true;
                    }
                    if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", techniqueDescription(technique));
                }
                ImGui::EndCombo();
            }
            break;
        }
        case LightSetting::Kind::DepthMode: {
            int mode = static_cast<int>(value);
            changed = ImGui::Combo(setting.label, &mode, "nearest\0midpoint\0second\0");
            edited = mode;
            break;
        }
        case LightSetting::Kind::Int: {
            int v = static_cast<int>(value);
            changed = ImGui::SliderInt(setting.label, &v, static_cast<int>(setting.min), static_cast<int>(setting.max),
                                       "%d", setting.logarithmic ? ImGuiSliderFlags_Logarithmic : 0);
            edited = v;
            break;
        }
        case LightSetting::Kind::Float: {
            auto v = static_cast<float>(value);
            // A length left automatic (kAutomatic) shows as "auto" until dragged to metres.
            changed = ImGui::SliderFloat(setting.label, &v, setting.min, setting.max, isAutomatic(v) ? "auto" : "%.4g",
                                         setting.logarithmic ? ImGuiSliderFlags_Logarithmic : 0);
            edited = v;
            break;
        }
    }
    if (ImGui::IsItemHovered() && setting.kind != LightSetting::Kind::Technique) {
        ImGui::SetTooltip("%s (Ctrl+click to type a value; out of range, the planner clamps it and warns)",
                          setting.key);
    }
    if (changed) {
        writeSetting(world, light, setting, edited);
        state.dirty = true;
    }
}

void drawLightStats(const ViewerState& state, int i) {
    if (i >= static_cast<int>(state.stats.lights.size())) return;
    const LightShadowStats& ls = state.stats.lights[static_cast<std::size_t>(i)];
    if (ls.mapSize == 0) {
        ImGui::TextDisabled("no map this frame (%s)", ls.technique.c_str());
        return;
    }
    ImGui::TextDisabled("map %d^2 x %d (asked %d), %.1f MB + chain %.1f MB", ls.mapSize, ls.layers, ls.requestedMapSize,
                        static_cast<double>(ls.mapBytes) / 1048576.0,
                        static_cast<double>(ls.filterChainBytes) / 1048576.0);
    ImGui::TextDisabled("layers drawn %d, reused %d, cleared %d; %d caster draws%s", ls.layersDrawn, ls.layersReused,
                        ls.layersCleared, ls.castersDrawn, ls.affectsView ? "" : "; out of view");
}

void drawLightsPanel(ViewerState& state) {
    const ImVec2 display = ImGui::GetIO().DisplaySize;
    ImGui::SetNextWindowPos(ImVec2(display.x - 400, 10), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSize(ImVec2(390, 0.6f * display.y), ImGuiCond_FirstUseEver);
    if (!ImGui::Begin("Lights")) {
        ImGui::End();
        return;
    }
    if (state.scene.lights.empty()) ImGui::TextDisabled("the scene has no lights");
    ImGui::PushItemWidth(ImGui::GetWindowWidth() * 0.5f);
    for (std::size_t i = 0; i < state.scene.lights.size(); ++i) {
        const Entity e = state.scene.lights[i];
        const Light* light = state.scene.world.tryGet<Light>(e);
        if (light == nullptr) continue;
        const std::string header = lightLabel(state, static_cast<int>(i)) + " (" + lightTypeName(light->type) + ")";
        ImGui::PushID(static_cast<int>(i));
        if (ImGui::CollapsingHeader(header.c_str(), ImGuiTreeNodeFlags_DefaultOpen)) {
            const Shadow* shadow = state.scene.world.tryGet<Shadow>(e);
            const ShadowTechnique technique = shadow != nullptr ? shadow->technique : ShadowTechnique::None;
            for (const LightSetting& setting : lightSettings()) {
                if (settingApplies(setting, light->type, technique)) settingWidget(state, e, setting);
            }
            drawLightStats(state, static_cast<int>(i));
        }
        ImGui::PopID();
    }
    ImGui::PopItemWidth();
    ImGui::End();
}

void drawTimingGraphs(const ViewerState& state) {
    const TimingHistory& h = state.history;
    if (h.filled == 0) return;
    for (int s = 0; s < TimingHistory::kSeries; ++s) {
        const auto& series = h.ms[static_cast<std::size_t>(s)];
        const int last = (h.next + TimingHistory::kFrames - 1) % TimingHistory::kFrames;
        float most = 0.0f;
        for (float v : series) most = std::max(most, v);
        char overlay[96];
        std::snprintf(overlay, sizeof(overlay), "%s %.2f ms (max %.1f)", TimingHistory::kNames[s],
                      static_cast<double>(series[static_cast<std::size_t>(last)]), static_cast<double>(most));
        ImGui::PlotLines(("##" + std::to_string(s)).c_str(), series.data(), TimingHistory::kFrames, h.next, overlay,
                         0.0f, std::max(most * 1.1f, 1.0f), ImVec2(ImGui::GetContentRegionAvail().x, 32.0f));
    }
}

void drawFramePanel(const ViewerState& state) {
    const ImVec2 display = ImGui::GetIO().DisplaySize;
    // Bottom centre, between the Scene panel (left) and the Lights panel (right).
    ImGui::SetNextWindowPos(ImVec2(400, display.y - 340), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSize(ImVec2(std::max(display.x - 810, 300.0f), 330), ImGuiCond_FirstUseEver);
    if (!ImGui::Begin("Frame")) {
        ImGui::End();
        return;
    }
    const FrameStats& s = state.stats;
    ImGui::TextWrapped("%s (%s), %dx%d", s.renderer.c_str(), s.timingMethod.c_str(), state.frameWidth,
                       state.frameHeight);
    drawTimingGraphs(state);
    ImGui::Text("shadow layers: drawn %d, reused %d, cleared %d", s.shadowLayersDrawn, s.shadowLayersReused,
                s.shadowLayersCleared);
    ImGui::Text("draws: shadow %d, main %d in %d passes; programs compiled %d", s.shadowDrawCalls, s.mainDrawCalls,
                s.mainPasses, s.programsCompiled);
    if (s.distanceFieldBytes > 0) {
        ImGui::Text("distance fields %.1f MB", static_cast<double>(s.distanceFieldBytes) / 1048576.0);
    }
    if (ImGui::TreeNode("passes", "passes (%zu)", s.passes.size())) {
        for (const PassTiming& p : s.passes) ImGui::Text("%8.2f ms  %s", p.ms, p.name.c_str());
        ImGui::TreePop();
    }
    if (s.warnings.empty() && state.scene.warnings.empty()) {
        ImGui::TextDisabled("no warnings");
    } else {
        ImGui::TextColored(kWarningColour, "warnings (%zu)", s.warnings.size() + state.scene.warnings.size());
        for (const std::vector<Warning>* list : {&state.scene.warnings, &s.warnings}) {
            for (const Warning& w : *list) {
                ImGui::TextColored(kWarningColour, "%s", warningCodeName(w.code));
                ImGui::SameLine();
                ImGui::TextWrapped("%s", w.message.c_str());
            }
        }
    }
    ImGui::End();
}

void drawShadowMapWindow(ViewerState& state) {
    ShadowMapView& map = state.mapView;
    if (!map.shown || state.mapTexture.id() == nullptr) return;
    const ImVec2 display = ImGui::GetIO().DisplaySize;
    ImGui::SetNextWindowPos(ImVec2(10, display.y - 320), ImGuiCond_FirstUseEver);
    const std::string title =
        "Shadow map: " + lightLabel(state, map.light) + ", layer " + std::to_string(map.layer) + "###shadowmap";
    if (ImGui::Begin(title.c_str(), &map.shown, ImGuiWindowFlags_AlwaysAutoResize)) {
        ImGui::Image(state.mapTexture.id(), ImVec2(256, 256));
        ImGui::TextDisabled("linear depth: near black, far white");
    }
    ImGui::End();
}

}  // namespace

void drawUi(ViewerState& state, UiRequests& requests) {
    drawFrameBackground(state);
    if (!state.showUi) return;
    drawScenePanel(state, requests);
    drawLightsPanel(state);
    drawFramePanel(state);
    drawShadowMapWindow(state);
}

}  // namespace shadow::viewer
