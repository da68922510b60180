// The light settings the viewer edits, as one table: the panels draw a widget per row and the
// script's `set` command looks keys up in it, so the two never disagree on a name or a range.
// Keys are the glTF `extras.shadow` keys (README, "glTF scenes"); ranges are the documented ones
// (components.h). An edit is written into the light's `Light` or `Shadow` component as given:
// the shadow planner clamps a value out of range and reports it as a frame warning.
#pragma once

#include <shadow/components.h>
#include <shadow/ecs.h>
#include <shadow/result.h>

#include <span>
#include <string>
#include <string_view>

namespace shadow::viewer {

/// One editable setting of a light.
struct LightSetting {
    enum class Kind { Int, Float, Technique, DepthMode };
    const char* key;    ///< glTF extras.shadow key, and the script's
    const char* label;  ///< what the panel shows
    Kind kind;
    float min;  ///< documented range, the slider's (the panel lets a typed value pass it)
    float max;
    bool logarithmic;  ///< slider on a log scale
    /// Which lights show it: a bit per `LightType` (1 directional, 2 spot, 4 point).
    unsigned lightTypes;
    /// Which techniques read it: a mask of `techniqueBit`s (every one: ~0u).
    unsigned techniques;
    /// Where the value lives: exactly one of these is set for Int and Float rows; Technique and
    /// DepthMode rows are `Shadow::technique` and `Shadow::depthMode`.
    float Light::*lightFloat = nullptr;
    float Shadow::*shadowFloat = nullptr;
    int Shadow::*shadowInt = nullptr;
};

/// Every editable setting, in panel order.
[[nodiscard]] std::span<const LightSetting> lightSettings();
/// The row whose key is `key`, or null.
[[nodiscard]] const LightSetting* findLightSetting(std::string_view key);
/// The keys, comma-separated, for messages.
[[nodiscard]] std::string lightSettingKeys();
/// Whether `setting` matters for a light of `type` with technique `technique`.
[[nodiscard]] bool settingApplies(const LightSetting& setting, LightType type, ShadowTechnique technique);

/// The value of `setting` on `light` (a `Shadow` field of a light without one: its default).
/// Techniques and depth modes as their enum values.
[[nodiscard]] double readSetting(const World& world, Entity light, const LightSetting& setting);
/// Writes `value` into `light`'s component (a `Shadow` field adds the component, with its
/// defaults, to a light without one). `value` is not clamped: the planner does that.
void writeSetting(World& world, Entity light, const LightSetting& setting, double value);
/// Parses `text` as a value of `setting`: a finite number (an integer for Int), or a technique or
/// depth-mode name this build offers. The error says what was expected.
[[nodiscard]] Result<double> parseSettingValue(const LightSetting& setting, std::string_view text);

}  // namespace shadow::viewer
