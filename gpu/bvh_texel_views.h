// bvh_texel_views.h - the descriptor set through which the trace kernels read the BVH as texel buffers
// (gpu/shaders/bvh_access.glsl explains why). Views cover min(buffer, maxTexelBufferElements) texels; when the
// BVH is larger, `covers()` is false and the kernels are specialised to read by device address instead.
#pragma once
#include <vulkan/vulkan.h>

#include "gpu/device_buffer.h"

namespace ht::gpu {

class BvhTexelViews {
 public:
  BvhTexelViews(VulkanContext::Impl& vk, VkDescriptorSetLayout layout, const DeviceBuffer& nodes,
                const DeviceBuffer& triangles);
  ~BvhTexelViews();
  BvhTexelViews(const BvhTexelViews&) = delete;
  BvhTexelViews& operator=(const BvhTexelViews&) = delete;

  VkDescriptorSet set() const { return set_; }
  bool covers() const { return covers_; }

 private:
  VkBufferView makeView(const DeviceBuffer& buffer, VkFormat format);
  VulkanContext::Impl& vk_;
  VkBufferView views_[4] = {};
  VkDescriptorPool pool_ = VK_NULL_HANDLE;
  VkDescriptorSet set_ = VK_NULL_HANDLE;
  bool covers_ = true;
};

}  // namespace ht::gpu
