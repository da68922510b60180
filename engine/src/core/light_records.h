// A shadow frame's lights as the records the shadow GLSL reads (gpu_records.h): used by the
// renderer's passes, by the shader inputs a game binds (ShadowShaderContract) and by the mask.
// Pure CPU. Here, below shadow/ and render/, so that both reach it.
#pragma once

#include <shadow/gpu_records.h>
#include <shadow/shadow_planner.h>

#include <glm/glm.hpp>

#include <string>
#include <vector>

namespace shadow::gpu {

/// `plan`'s light as the shader reads it, positions relative to `wsCamera`, with its shadow when
/// it has a map (technique None otherwise) in pass slot `slot`: its layers go to
/// `slotLayers[0 .. layers)`, which is `layers[slot * SG_MAX_LAYERS_PER_LIGHT]` of the block.
GpuLight packSlot(const ShadowLightPlan& plan, const glm::dvec3& wsCamera, int slot, GpuShadowLayer* slotLayers);

/// The layer record of `layer`, its matrices made to take camera-relative positions.
GpuShadowLayer packLayer(const ShadowLayerPlan& layer, const glm::dvec3& wsCamera);

/// Best-candidate (Mitchell) Poisson disk of `count` points in the unit disk: each point is the
/// candidate farthest from those before it, so every prefix is well spread. Deterministic.
std::vector<glm::vec2> poissonDisk(int count);

}  // namespace shadow::gpu
