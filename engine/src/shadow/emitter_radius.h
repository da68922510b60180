// The automatic filter widths: PCF and VSM's radius (`Shadow::pcfRadius` when automatic), the
// penumbra the light's own emitter casts from a typical caster of its layers, so that a
// fixed-width filter follows the light and the scene instead of a length in metres; and every
// filter's widest radius (`Shadow::maxFilterTexels` when automatic), the widest penumbra its
// casters can cast.
#pragma once

#include "shadow/light_projection.h"
#include "shadow/scene_geometry.h"

#include <span>
#include <vector>

namespace shadow {

/// The half-width (m at the receiver) of the penumbra that light `light`, whose emitter has size
/// `emitterSize` (`Light::radius` in m, `Light::angularRadius` in rad for a directional light),
/// casts from a typical caster of its `layers`: each caster's narrowest penumbra (its box's
/// corner nearest the receiver behind it along the light's ray, where the ray leaves the
/// receivers' bounds `geometry.receivers`, by similar triangles as shaders/shadow_penumbra.glsl's
/// sg_penumbraRadius, a spot's disk foreshortened as it looks from the receiver), the median
/// over the casters (`ShadowLayerPlan::casters`, bounds from `geometry.casters`); 0 without an
/// emitter, casters or receivers behind them. The narrowest, because a fixed filter wider than a
/// caster's contact shadow blurs the contact, where a caster resting on its receiver (the usual
/// case) casts most of its outline: a floating caster gets its gap's penumbra, a resting one none
/// (the one-texel minimum). `scratch` is reused storage.
[[nodiscard]] double emitterFilterRadius(const LayerInputs& light, double emitterSize, const SceneGeometry& geometry,
                                         std::span<const ShadowLayerPlan> layers, std::vector<double>& scratch);

/// The widest penumbra (half-width in texels of the receiver's layer) light `light` casts from
/// the casters of `layers`: over every corner of every caster's box (in every layer it is in),
/// the penumbra across the gap to the receiver behind it along the ray (as
/// `emitterFilterRadius`), over the texel of that layer where the ray meets the receiver (a
/// cascade's one size; a perspective layer's grows with the axial distance). 0 without an
/// emitter, casters or receivers behind them.
[[nodiscard]] double widestPenumbraTexels(const LayerInputs& light, double emitterSize, const SceneGeometry& geometry,
                                          std::span<const ShadowLayerPlan> layers);

}  // namespace shadow
