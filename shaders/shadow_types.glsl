// The GLSL side of gpu_structs.h (the C++ side is engine/include/shadow/gpu_records.h): the
// records C++ and GLSL share, as GLSL structs named sg_GpuLight and sg_GpuShadowLayer.
#ifndef SG_SHADOW_TYPES
#define SG_SHADOW_TYPES
#include "shared_constants.h"
#define SG_STRUCT(name) struct sg_##name {
#define SG_END_STRUCT };
#define SG_VEC3 vec3
#define SG_MAT4 mat4
#define SG_FLOAT float
#define SG_INT int
#include "gpu_structs.h"
#endif
