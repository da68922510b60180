// C++ side of gpu_structs.h: the same struct declarations in glm types with std430
// alignment, so the buffers the engine fills are the layout the shaders read.
#pragma once

#include <glm/glm.hpp>

#include <cstdint>

#include "shared_constants.h"

namespace shadow::gpu {

#define SG_STRUCT(name) struct name {
#define SG_END_STRUCT \
    }                 \
    ;
#define SG_VEC3 alignas(16) glm::vec3
#define SG_MAT4 alignas(16) glm::mat4
#define SG_FLOAT float
#define SG_INT std::int32_t
#include "gpu_structs.h"
#undef SG_STRUCT
#undef SG_END_STRUCT
#undef SG_VEC3
#undef SG_MAT4
#undef SG_FLOAT
#undef SG_INT

// std430 rounds a struct's array stride up to its alignment (16); so does alignas in C++.
static_assert(sizeof(GpuLight) % 16 == 0 && sizeof(GpuLight) == 160);
static_assert(sizeof(GpuShadowLayer) % 16 == 0 && sizeof(GpuShadowLayer) == 160);

}  // namespace shadow::gpu
