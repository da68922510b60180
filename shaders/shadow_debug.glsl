// Debug outputs of the shadow code (--debug cascade|blocker|penumbra|visibility): compiled only
// into the debug variant, so production variants carry no debug stores.
#ifndef SG_SHADOW_DEBUG
#define SG_SHADOW_DEBUG
#ifdef SG_DEBUG_VIEWS
float sg_debugBlockerDepth = 0.0;  // m, last soft-shadow evaluation
float sg_debugPenumbra = 0.0;      // m, last soft-shadow evaluation
int sg_debugCascade = 0;
#define SG_DEBUG_STORE(variable, value) variable = (value)
#else
#define SG_DEBUG_STORE(variable, value)
#endif
#endif
