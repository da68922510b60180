// The resolution at which screen-space visibility is computed for filtered shadows: one rule for
// the renderer's screen-space stage (render/screen_visibility.h) and the game-facing mask
// (shadow_mask.h). Pure CPU.
#pragma once

#include <shadow/shared_constants.h>

#include <algorithm>

namespace shadow {

/// Whether technique `t` (SG_TECH_*) filters its shadows: any but none and hard, whose edges need
/// every pixel.
[[nodiscard]] constexpr bool filtersShadows(int t) { return t != SG_TECH_NONE && t != SG_TECH_HARD; }

/// Rows below which filtered shadows are computed at full resolution: there penumbrae are too
/// few pixels wide for half resolution. Measured against the truth (BENCHMARKS.md, error against
/// time, rows screen-half): on builtin:default at 320x240 the upsample added 11 % (PCSS) and
/// 33 % (sdf) to the error; at 640x360 up to 7 % (PCSS) and 10 % (sdf) on its spot, within 2 %
/// on its other lights, and on the bunny spots none.
inline constexpr int kMinStageHeight = 360;
/// Rows from which filtered shadows are computed at quarter resolution: a penumbra is as many
/// samples wide there as at half resolution in an image of `kMinStageHeight` rows, the spacing
/// measured to keep the error (BENCHMARKS.md, screen-space visibility: at 1280x720 the
/// quarter-resolution stage against forward).
inline constexpr int kMinQuarterStageHeight = 2 * kMinStageHeight;

/// The divisor of the screen resolution for the visibility of a group of lights of
/// `techniques` (SG_TECH_*) in an image of `height` rows: 1 when none of them filters its
/// shadows (`filtersShadows`) or under `kMinStageHeight` rows, 4 from `kMinQuarterStageHeight`
/// rows, else 2. (`Techniques`: a span of the slots' constants, as the lit passes or the mask
/// store them.)
template <typename Techniques>
[[nodiscard]] constexpr int stageDivisor(Techniques techniques, int height) {
    const auto filters = [](int t) { return filtersShadows(t); };
    if (height < kMinStageHeight || std::none_of(techniques.begin(), techniques.end(), filters)) return 1;
    return height >= kMinQuarterStageHeight ? 4 : 2;
}

/// Whether the refine after a resolve recomputes only the lights the resolve marked at a pixel,
/// for a group of lights of `techniques` (as `stageDivisor` takes them): with three or more
/// shadowed lights. With fewer, the lights' guards and the resolve's prior cost more than they
/// save: at 1280x720, paired runs, the resolve +1.5-2.5 ms and the refine +1-2 ms on the
/// two-light sample scenes `character` and `fence` (their frames +2-6 %), a refine 1-5 ms dearer
/// with one light; with three and more a refine of a quarter less on `courtyard` (9 lights) and
/// on builtin:default's `sdf`.
inline constexpr int kMinPerLightRefineLights = 3;
template <typename Techniques>
[[nodiscard]] constexpr bool refinesPerLight(Techniques techniques) {
    return std::count_if(techniques.begin(), techniques.end(), [](int t) { return t != SG_TECH_NONE; }) >=
           kMinPerLightRefineLights;
}

}  // namespace shadow
