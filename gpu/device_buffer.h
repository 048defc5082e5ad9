// device_buffer.h - a Vulkan buffer with its own memory, addressed from shaders by device address.
#pragma once
#include <vulkan/vulkan.h>

#include <cstddef>
#include <cstdint>
#include <vector>

#include "gpu/vulkan_impl.h"

namespace ht::gpu {

enum class MemoryPlace { Device, HostReadback };

class DeviceBuffer {
 public:
  DeviceBuffer() = default;
  DeviceBuffer(VulkanContext::Impl& vk, VkDeviceSize size, MemoryPlace place);
  ~DeviceBuffer();
  DeviceBuffer(DeviceBuffer&& other) noexcept;
  DeviceBuffer& operator=(DeviceBuffer&& other) noexcept;
  DeviceBuffer(const DeviceBuffer&) = delete;
  DeviceBuffer& operator=(const DeviceBuffer&) = delete;

  VkBuffer handle() const { return buffer_; }
  VkDeviceAddress address() const { return address_; }
  VkDeviceSize size() const { return size_; }
  void* mapped() const { return mapped_; }  // null when the memory is not host visible

  // Host -> buffer and buffer -> host copies; through a staging buffer of their own when the memory is not mapped
  // (StagingBuffer keeps one for copies that repeat).
  void upload(const void* data, VkDeviceSize bytes, VkDeviceSize offset = 0);
  void download(void* data, VkDeviceSize bytes, VkDeviceSize offset = 0) const;

 private:
  void release();
  VulkanContext::Impl* vk_ = nullptr;
  VkBuffer buffer_ = VK_NULL_HANDLE;
  VkDeviceMemory memory_ = VK_NULL_HANDLE;
  VkDeviceAddress address_ = 0;
  VkDeviceSize size_ = 0;
  void* mapped_ = nullptr;
};

// A host-visible buffer kept for the copies between host memory and device buffers that are not mapped (device-local
// memory of a discrete GPU): a node move's uploads reuse it (GpuScene::moveInstances) instead of allocating, mapping
// and freeing a staging buffer at every move. It grows to the largest copy and never shrinks. A mapped buffer is
// copied in place, without it. (Frames need none: the GPU writes them into host memory, OutputBuffers::image.)
class StagingBuffer {
 public:
  explicit StagingBuffer(VulkanContext::Impl& vk) : vk_(&vk) {}
  void upload(DeviceBuffer& to, const void* data, VkDeviceSize bytes, VkDeviceSize offset = 0);
  void download(const DeviceBuffer& from, void* data, VkDeviceSize bytes, VkDeviceSize offset = 0);
  // The staging buffer, at least `bytes` large (host visible, mapped).
  DeviceBuffer& reserve(VkDeviceSize bytes);
  VkDeviceSize size() const { return buffer_.size(); }

 private:
  VulkanContext::Impl* vk_;
  DeviceBuffer buffer_;
};

// Several host -> buffer copies through one staging buffer and one submission (DeviceBuffer::upload pays a submit
// and a fence wait per call): e.g. the ranges a node move changes (GpuScene::moveInstances). The data is copied at
// add(); nothing reaches the buffers before submit(). `staging`: a kept staging buffer (else one for this batch).
class UploadBatch {
 public:
  explicit UploadBatch(VulkanContext::Impl& vk, StagingBuffer* staging = nullptr) : vk_(vk), staging_(staging) {}
  void add(DeviceBuffer& buffer, const void* data, VkDeviceSize bytes, VkDeviceSize offset = 0);
  void submit();

 private:
  struct Copy {
    DeviceBuffer* buffer;
    VkDeviceSize offset, bytes, stagingOffset;
  };
  VulkanContext::Impl& vk_;
  StagingBuffer* staging_;
  std::vector<Copy> copies_;
  std::vector<unsigned char> staged_;
};

// Records and runs a one-off command buffer synchronously (uploads, small jobs).
class OneShotCommands {
 public:
  explicit OneShotCommands(VulkanContext::Impl& vk);
  ~OneShotCommands();
  OneShotCommands(const OneShotCommands&) = delete;
  OneShotCommands& operator=(const OneShotCommands&) = delete;
  VkCommandBuffer cmd() const { return cmd_; }
  void submitAndWait();

 private:
  VulkanContext::Impl& vk_;
  VkCommandBuffer cmd_ = VK_NULL_HANDLE;
  VkFence fence_ = VK_NULL_HANDLE;
};

}  // namespace ht::gpu
