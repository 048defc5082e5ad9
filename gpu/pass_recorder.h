// pass_recorder.h - records compute passes into a command buffer with a barrier after each and GPU
// timestamps around each, so every frame gets a per-pass time breakdown (raygen, trace, shade, ...).
#pragma once
#include <vulkan/vulkan.h>

#include <array>
#include <cstdint>
#include <vector>

#include "gpu/compute_pipeline.h"
#include "gpu/wavefront_types.h"

namespace ht::gpu {

enum class Stage : std::uint32_t {
  Raygen,
  Trace,
  Shade,
  Shadow,
  Queues,
  Resolve,
  Refine,
  Interleave,
  Record,
  Mark,
  Count
};
const char* stageName(Stage stage);

class PassRecorder {
 public:
  // Binds `bvhSet` (set 0: the BVH texel views) for every pass recorded.
  PassRecorder(VkCommandBuffer cmd, VkPipelineLayout layout, VkDescriptorSet bvhSet, VkQueryPool pool,
               std::uint32_t queryCapacity);

  void dispatch(const ComputePipeline& pipeline, const gpu_shared::PassConstants& pc, std::uint32_t groups,
                Stage stage);
  // A grid of groups.x x groups.y x groups.z workgroups.
  void dispatch(const ComputePipeline& pipeline, const gpu_shared::PassConstants& pc, glm::uvec3 groups, Stage stage);
  void dispatchIndirect(const ComputePipeline& pipeline, const gpu_shared::PassConstants& pc, VkBuffer args,
                        VkDeviceSize offset, Stage stage);
  // Adds the elapsed GPU time of every recorded pass to `ms` (by stage); call after the submit finished.
  void collect(VkDevice device, float timestampPeriodNs,
               std::array<double, static_cast<size_t>(Stage::Count)>& ms) const;
  // After collect(), with the command buffer begun again: records into it from the first query.
  void restart();

 private:
  void begin(const ComputePipeline& pipeline, const gpu_shared::PassConstants& pc, Stage stage);
  void end();
  VkCommandBuffer cmd_;
  VkPipelineLayout layout_;
  VkDescriptorSet bvhSet_;
  VkQueryPool pool_;
  std::uint32_t capacity_;
  std::uint32_t next_ = 0;
  std::vector<Stage> stages_;  // one per query pair
};

}  // namespace ht::gpu
