// frame_descriptors.h - descriptor set 0 of every pass: texel-buffer views over the scene, BVH and per-path
// buffers plus the FrameBlock uniform buffer (gpu/shaders/common.glsl explains why texel buffers). Views are
// created when a binding's buffer changes and written to the set in one update before recording.
#pragma once
#include <vulkan/vulkan.h>

#include <array>

#include "gpu/device_buffer.h"
#include "gpu/wavefront_types.h"

namespace ht::gpu {

class FrameDescriptors {
 public:
  FrameDescriptors(VulkanContext::Impl& vk, VkDescriptorSetLayout layout);
  ~FrameDescriptors();
  FrameDescriptors(const FrameDescriptors&) = delete;
  FrameDescriptors& operator=(const FrameDescriptors&) = delete;

  // Read-only view (uniform texel buffer). Views are clamped to maxTexelBufferElements; returns whether the
  // whole buffer is covered (callers that cannot fall back treat false as an error). `fresh` as below.
  bool setUniformTexels(std::uint32_t binding, const DeviceBuffer& buffer, VkFormat format, bool fresh = false);
  // Read-write view (storage texel buffer); throws GpuError if the buffer exceeds maxTexelBufferElements.
  // `fresh`: the buffer is new even if its handle equals the previous one's (drivers reuse handles of
  // destroyed buffers), so the view must be rebuilt.
  void setStorageTexels(std::uint32_t binding, const DeviceBuffer& buffer, VkFormat format, bool fresh);
  void setUniformBuffer(std::uint32_t binding, const DeviceBuffer& buffer);
  void flush();  // writes every binding changed since the last flush
  VkDescriptorSet set() const { return set_; }

  static VkDescriptorType bindingType(std::uint32_t binding);

 private:
  struct Binding {
    VkBuffer buffer = VK_NULL_HANDLE;
    VkFormat format = VK_FORMAT_UNDEFINED;
    VkBufferView view = VK_NULL_HANDLE;
    VkDeviceSize range = 0;
    bool dirty = false;
  };
  bool setView(std::uint32_t binding, const DeviceBuffer& buffer, VkFormat format, bool fresh);
  VulkanContext::Impl& vk_;
  VkDescriptorPool pool_ = VK_NULL_HANDLE;
  VkDescriptorSet set_ = VK_NULL_HANDLE;
  std::array<Binding, gpu_shared::HT_BINDING_COUNT> bindings_{};
};

}  // namespace ht::gpu
