// compute_pipeline.h - compute pipelines built from the SPIR-V embedded at build time, with specialisation
// constants, all sharing one layout: the PassConstants push-constant block plus descriptor set 0
// (gpu/frame_descriptors.h).
#pragma once
#include <vulkan/vulkan.h>

#include <cstdint>
#include <span>
#include <vector>

#include "gpu/vulkan_impl.h"

namespace ht::gpu {

enum class ShaderId {
  Raygen,
  TraceClosest,
  TraceAny,
  Shade,
  Prepare,
  GatherDirect,
  Resolve,
  Interleave,
  RefineSelect,
  AccumShow,
  RecordSegments,
  MarkDirty,
  MarkAccumulated
};

std::span<const std::uint32_t> embeddedSpirv(ShaderId id);
const char* shaderName(ShaderId id);

class PipelineLayout {
 public:
  explicit PipelineLayout(VulkanContext::Impl& vk);
  ~PipelineLayout();
  PipelineLayout(const PipelineLayout&) = delete;
  PipelineLayout& operator=(const PipelineLayout&) = delete;
  VkPipelineLayout handle() const { return layout_; }
  VkDescriptorSetLayout setLayout() const { return setLayout_; }

 private:
  VulkanContext::Impl& vk_;
  VkDescriptorSetLayout setLayout_ = VK_NULL_HANDLE;
  VkPipelineLayout layout_ = VK_NULL_HANDLE;
};

class ComputePipeline {
 public:
  // specialization[i] is the value of constant_id = i (32-bit; booleans as 0/1).
  ComputePipeline(VulkanContext::Impl& vk, const PipelineLayout& layout, ShaderId shader,
                  const std::vector<std::uint32_t>& specialization = {});
  ~ComputePipeline();
  ComputePipeline(const ComputePipeline&) = delete;
  ComputePipeline& operator=(const ComputePipeline&) = delete;
  VkPipeline handle() const { return pipeline_; }

 private:
  VulkanContext::Impl& vk_;
  VkPipeline pipeline_ = VK_NULL_HANDLE;
};

}  // namespace ht::gpu
