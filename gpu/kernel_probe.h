// kernel_probe.h - runs small shared C++/GLSL functions on the GPU on their own (no scene, no renderer), so tests
// can compare the GPU build of a shared header with its C++ build bit for bit.
#pragma once
#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "bvh/two_level_bvh.h"
#include "gpu/vulkan_context.h"

namespace ht::gpu {

struct OffsetRayProbeInput {
  glm::vec3 p;  // hit point
  glm::vec3 n;  // normal (finite), the side the new ray leaves towards
};

// ht_offset_ray(p, n) (bvh/offset_ray.h) evaluated by gpu/shaders/offset_ray_probe.comp, one result per input, in
// order. Throws GpuError on a Vulkan failure.
std::vector<glm::vec3> runOffsetRayProbe(VulkanContext& context, std::span<const OffsetRayProbeInput> inputs);

// For each input (a, b, x, -): (ht_div(a, b), ht_sqrt(x), ht_div3(vec3(a, x, b), b).y, 0) (common/exact_division.h)
// evaluated by gpu/shaders/exact_math_probe.comp, in order. Throws GpuError on a Vulkan failure.
std::vector<glm::vec4> runExactMathProbe(VulkanContext& context, std::span<const glm::vec4> inputs);

// ht_trace_two_level_ordered (bvh/ordered_traversal.h) over `bvh`'s buffers, evaluated by
// gpu/shaders/two_level_probe.comp: one result per ray, in order (hit, steps, overflow). Throws GpuError on a Vulkan
// failure.
std::vector<gpu_shared::HtTraceResult> runTwoLevelProbe(VulkanContext& context, const bvh::TwoLevelBvh& bvh,
                                                        std::span<const gpu_shared::HtRay> rays,
                                                        std::uint32_t stepLimit = gpu_shared::HT_TRAVERSAL_STEP_LIMIT);

}  // namespace ht::gpu
