// Debug outputs of the shadow code (--debug cascade|blocker|penumbra|visibility|steps|closest): compiled only
// into the debug variant, so production variants carry no debug stores.
#ifndef SG_SHADOW_DEBUG
#define SG_SHADOW_DEBUG
#ifdef SG_DEBUG_VIEWS
float sg_debugBlockerDepth = 0.0;  // m, last soft-shadow evaluation
float sg_debugPenumbra = 0.0;      // m, last soft-shadow evaluation
int sg_debugCascade = 0;
float sg_debugMarchSteps = 0.0;  // sdf: steps the last march took
float sg_debugClosest = 0.0;     // sdf: its smallest clearance over the cone's radius, in [-1, 1]
#define SG_DEBUG_STORE(variable, value) variable = (value)
#else
#define SG_DEBUG_STORE(variable, value)
#endif
#endif
