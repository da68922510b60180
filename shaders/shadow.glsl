// The public shadow GLSL (engine/include/shadow/shadow_shaders.h): what a game's own shader
// includes to get the visibility the module's renderer computes, with the same code. Every name
// it declares starts with sg_ or SG_.
//
// Before including it, a shader may define the binding points and units (SG_BINDING_LIGHTS,
// SG_BINDING_LAYERS, SG_BINDING_KERNELS, SG_UNIT_SHADOW_COMPARE, SG_UNIT_SHADOW_DEPTH,
// SG_UNIT_SHADOW_MINMAX; defaults in shared_constants.h) and must define the techniques it wants
// compiled (SG_TECH_<NAME>_ENABLED; shadow_techniques.glsl lists them); a light whose technique
// is not compiled reads as lit. shadowShaderSource() writes those defines and expands the
// includes, with only the code of the techniques asked for.
#ifndef SG_SHADOW_PUBLIC
#define SG_SHADOW_PUBLIC
// A game's calls cannot be counted: every loop of the shadow code stands in a loop of its own
// (shadow_bindings.glsl, SG_ISOLATED), so that any number of calls compiles in linear time.
#ifndef SG_ISOLATE_LOOPS
#define SG_ISOLATE_LOOPS
#endif
#include "shadow_visibility.glsl"
#include "shadow_surface.glsl"

// Visibility in [0, 1] of the light in slot `slot` (dynamically uniform) of the inputs bound
// (ShadowSystem::shaderInputs) at camera-relative position `csPosition` of surface `s`;
// `viewDistance` is the distance along the camera's forward axis (cascade choice).
float sg_lightVisibility(int slot, vec3 csPosition, sg_Surface s, float viewDistance) {
    return sg_shadowVisibility(slot, sg_lights[slot], csPosition, s.normal, s.geoNormal, s.curvature, viewDistance);
}
#endif
