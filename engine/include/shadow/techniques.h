// The one table of shadow techniques. Everything that names or selects a technique is made from
// it or checked against it: the `ShadowTechnique` enum and its names (glTF, CLI, stats.json),
// the GLSL constants (SG_TECH_* in shared_constants.h, checked at compile time), the GLSL each
// program compiles (shaders/shadow_techniques.glsl and the dispatch the engine writes per
// program), the filter chain a light's map carries, the CLI's help and the README's table
// (tests/gl/technique_glsl_test.cpp).
//
// Adding a technique is one row here, its constant in shared_constants.h, and one GLSL include
// in shaders/ defining `sg_<glsl>Policy()` (its share of bias and normal offset) and
// `sg_<glsl>Visibility(slot, light, receiver)`; shaders/README.md says how.
#pragma once

#include <cstdint>
#include <initializer_list>

/// X(Enum, CONSTANT, "name", "include", glsl, Chain, Loops, Availability, "description"):
///   Enum          the `ShadowTechnique` enumerator; rows are in the order of the enum's values;
///   CONSTANT      GLSL constant SG_TECH_<CONSTANT> (the enum's value) and the define
///                 SG_TECH_<CONSTANT>_ENABLED that compiles the technique's code in;
///   "name"        how glTF `extras.shadow.technique`, the CLI and stats.json spell it;
///   "include"     the file of shaders/ with its code ("" for None);
///   glsl          the stem of its GLSL functions: sg_<glsl>Policy, sg_<glsl>Visibility;
///   Chain         the filter chain its map carries: None, MinMax (min/max depth pyramid),
///                 Moments (two-moment mips), FourMoments (four-moment mips), SummedMoments
///                 (summed-area table of two moments);
///   Loops         the loops with run-time trip counts its code runs one after another (its
///                 taps): what the compile-time guard of lit.frag.glsl counts (gl/technique_glsl.h);
///   Availability  Public, or Baseline: the benchmarks' reference, compiled only into builds
///                 with SHADOW_BASELINE_TECHNIQUES and never into a game's shader;
///   "description" one line for the CLI's help and the README.
#define SHADOW_TECHNIQUE_TABLE(X)                                                                                 \
    X(None, NONE, "none", "", none, None, 0, Public, "no shadow map; visibility 1")                               \
    X(Hard, HARD, "hard", "shadow_hard.glsl", hard, None, 0, Public,                                              \
      "one depth comparison, bilinear over the 2x2 texels around the receiver")                                   \
    X(Pcf, PCF, "pcf", "shadow_pcf.glsl", pcf, MinMax, 1, Public,                                                 \
      "percentage-closer filtering over `pcfRadius` at the receiver")                                             \
    X(Pcss, PCSS, "pcss", "shadow_pcss.glsl", pcss, MinMax, 2, Public,                                            \
      "percentage-closer soft shadows: blocker search, penumbra from the emitter's size, PCF over it")            \
    X(PcssTextbook, PCSS_TEXTBOOK, "pcss-textbook", "shadow_pcss_textbook.glsl", pcssTextbook, None, 2, Baseline, \
      "the seeds' PCSS, fixed Poisson taps around the receiver's map position (benchmark builds only)")           \
    X(Vsm, VSM, "vsm", "shadow_vsm.glsl", vsm, Moments, 0, Public,                                                \
      "variance shadow map: Chebyshev's bound over prefiltered depth moments of a `pcfRadius` region")            \
    X(Vssm, VSSM, "vssm", "shadow_vssm.glsl", vssm, SummedMoments, 1, Public,                                     \
      "variance soft shadows: blocker depth and penumbra from a summed-area table of the moments")                \
    X(Msm, MSM, "msm", "shadow_msm.glsl", msm, None, 0, Public,                                                   \
      "moment shadow map: the Hamburger bound of four moments over one texel, edges antialiased")                 \
    X(MsmSoft, MSM_SOFT, "msm-soft", "shadow_msm_soft.glsl", msmSoft, FourMoments, 0, Public,                     \
      "moment soft shadows: vssm's blocker search and penumbra, the Hamburger bound over it")                     \
    X(Sdf, SDF, "sdf", "shadow_sdf.glsl", sdf, None, 5, Public,                                                   \
      "distance-field soft shadows: a cone marched to the emitter through the casters' signed distance fields")

namespace shadow {

/// How a light's visibility is computed from its shadow map (one enumerator per row of
/// `SHADOW_TECHNIQUE_TABLE`; the table says what each does).
enum class ShadowTechnique : std::uint8_t {
#define SHADOW_TECHNIQUE_ENUMERATOR(Enum, ...) Enum,
    SHADOW_TECHNIQUE_TABLE(SHADOW_TECHNIQUE_ENUMERATOR)
#undef SHADOW_TECHNIQUE_ENUMERATOR
};

/// Number of techniques (rows of the table).
inline constexpr int kShadowTechniqueCount = static_cast<int>(std::initializer_list<ShadowTechnique>{
#define SHADOW_TECHNIQUE_COUNT(Enum, ...) ShadowTechnique::Enum,
    SHADOW_TECHNIQUE_TABLE(SHADOW_TECHNIQUE_COUNT)
#undef SHADOW_TECHNIQUE_COUNT
}
                                                                  .size());

/// Bit `1 << t` for technique t: sets of techniques (e.g. `shadowShaderSource`'s) are masks.
constexpr unsigned techniqueBit(ShadowTechnique t) { return 1u << static_cast<unsigned>(t); }

/// Every technique with a shadow map that a game may use (the table's Public rows but None).
inline constexpr unsigned kAllShadowTechniques = 0u
#define SHADOW_TECHNIQUE_PUBLIC_BIT(Enum, C, N, I, G, Chain, Loops, Availability, ...)                                 \
    | (ShadowTechnique::Enum != ShadowTechnique::None && #Availability[0] == 'P' ? techniqueBit(ShadowTechnique::Enum) \
                                                                                 : 0u)
    SHADOW_TECHNIQUE_TABLE(SHADOW_TECHNIQUE_PUBLIC_BIT)
#undef SHADOW_TECHNIQUE_PUBLIC_BIT
    ;

}  // namespace shadow
