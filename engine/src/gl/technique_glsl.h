// The GLSL of the shadow techniques a program compiles, written from the technique table
// (shadow/techniques.h): the SG_TECH_*_ENABLED defines, and shadow_techniques.glsl, which
// includes each technique's file and dispatches on the light's technique.
#pragma once

#include <shadow/shared_constants.h>
#include <shadow/techniques.h>

#include <span>
#include <string>
#include <vector>

namespace shadow::gpu {

/// The file name under which programs include the technique dispatch.
inline constexpr const char* kTechniquesFile = "shadow_techniques.glsl";

/// Appends `SG_TECH_<CONSTANT>_ENABLED` for every technique whose bit (`techniqueBit`) is set in
/// `techniques`, None excepted.
void appendTechniqueDefines(unsigned techniques, std::vector<std::string>& defines);

/// shadow_techniques.glsl for a program compiling exactly `techniques` (None's bit ignored): the
/// include of each one's file, `sg_techniquePolicy(technique)` and `sg_techniqueVisibility(slot,
/// light, receiver)`, and nothing of the other techniques. A light whose technique is not in the
/// set reads as lit. Each technique's call stands in a loop of 0 or 1 trips: a dispatch on a
/// technique known only at run time (a game's shader) then costs a CPU rasteriser only the
/// technique the light has (it runs both sides of an `if`, but no loop nobody enters).
[[nodiscard]] std::string techniquesGlsl(unsigned techniques);

/// The installed shaders/shadow_techniques.glsl, for a game that expands includes itself: every
/// Public technique, each under `#ifdef SG_TECH_<CONSTANT>_ENABLED`, the files they share
/// included unconditionally first (so that a loader that includes each file once still finds
/// them). The checked-in file must equal it (tests/gl/technique_glsl_test.cpp).
[[nodiscard]] std::string installedTechniquesGlsl();

/// The GLSL function of shadow_techniques.glsl that gives the visibility of a light with
/// technique `t` without the dispatch (`sg_<glsl>LightVisibility`; for None a function that
/// returns 1): what a pass that knows a slot's technique when compiling calls
/// (SG_SLOT<i>_VISIBILITY).
[[nodiscard]] std::string slotVisibilityFunction(ShadowTechnique t);

/// One slot of a pass as its program is specialised: SG_LIGHT_*, SG_TECH_*, SG_KERNEL_*.
struct SlotConfig {
    int type = SG_LIGHT_POINT;
    int technique = SG_TECH_NONE;
    int kernel = SG_KERNEL_VOGEL;
    bool operator==(const SlotConfig&) const = default;
};

/// Shadowed slots a pass compiles as straight-line code each; a pass with more runs the slots of
/// equal configuration as one group (below).
inline constexpr int kMaxStraightLineSlots = 4;

/// Loops with run-time trip counts a program may run in sequence before its loops are isolated
/// (SG_ISOLATE_LOOPS, shadow_bindings.glsl): up to here LLVM's analysis of them costs llvmpipe
/// under a quarter of a second (measured: 12 loops 0.9 s, 16 loops 44 s).
inline constexpr int kMaxLoopsInSequence = 8;

/// Appends the defines of a pass's slots, grouped: SG_PASS_GROUPS, and for every group g <
/// `capacity` SG_GROUP<g>_COUNT, _SLOTS (a GLSL int[] of its slots), _FIRST (its first slot, a
/// constant the compiler folds where a constant array's element may not be), _TYPE, _TECH, _KERNEL and
/// _VISIBILITY (`slotVisibilityFunction`); groups beyond the pass's are inert (no technique).
/// A group's code is compiled once, in a loop over its slots when it has more than one
/// (lit.frag.glsl). Up to kMaxStraightLineSlots shadowed slots each make a group of their own:
/// straight-line code with constant sampler indices, the fastest to run. Beyond that, slots of
/// equal configuration share one, so eight lights alike compile like one: a slot's code in a
/// loop indexes the samplers dynamically, which costs a CPU rasteriser its taps' time again
/// (measured: +10-28 % for PCSS and PCF lights), where eight straight-line copies of a filter cost
/// seconds of compilation (tests/render/lit_programs_compile_test.cpp). SG_ISOLATE_LOOPS when the
/// straight-line lights' loops (the technique table's Loops column, one more for a point light's
/// face crossing and for a sun's cascade blend) exceed kMaxLoopsInSequence.
void appendSlotGroupDefines(std::span<const SlotConfig> slots, int capacity, std::vector<std::string>& defines);

/// The technique's GLSL file, "" for None.
[[nodiscard]] const char* techniqueGlslFile(ShadowTechnique t);

}  // namespace shadow::gpu
