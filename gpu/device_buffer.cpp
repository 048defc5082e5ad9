// device_buffer.cpp - buffer allocation (one allocation per buffer: holotrace allocates few, large buffers).
#include "gpu/device_buffer.h"

#include <cstring>
#include <utility>

namespace ht::gpu {

namespace {

uint32_t findMemoryType(const VkPhysicalDeviceMemoryProperties& props, uint32_t typeBits,
                        VkMemoryPropertyFlags required, VkMemoryPropertyFlags preferred) {
  int fallback = -1;
  for (uint32_t i = 0; i < props.memoryTypeCount; ++i) {
    if (!(typeBits & (1u << i))) continue;
    VkMemoryPropertyFlags flags = props.memoryTypes[i].propertyFlags;
    if ((flags & required) != required) continue;
    if ((flags & preferred) == preferred) return i;
    if (fallback < 0) fallback = static_cast<int>(i);
  }
  if (fallback < 0) throw GpuError("no Vulkan memory type with the required properties");
  return static_cast<uint32_t>(fallback);
}

constexpr VkBufferUsageFlags kUsage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT |
                                      VK_BUFFER_USAGE_TRANSFER_DST_BIT | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT |
                                      VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT | VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT |
                                      VK_BUFFER_USAGE_STORAGE_TEXEL_BUFFER_BIT | VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT;

}  // namespace

DeviceBuffer::DeviceBuffer(VulkanContext::Impl& vk, VkDeviceSize size, MemoryPlace place) : vk_(&vk), size_(size) {
  if (size > vk.info.maxMemoryAllocationSize) {
    throw GpuError("buffer of " + std::to_string(size >> 20) + " MiB exceeds the device's maxMemoryAllocationSize of " +
                   std::to_string(vk.info.maxMemoryAllocationSize >> 20) + " MiB");
  }
  VkBufferCreateInfo bci{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  bci.size = size < 16 ? 16 : size;
  bci.usage = kUsage;
  bci.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  HT_VK(vkCreateBuffer(vk.device, &bci, nullptr, &buffer_));
  VkMemoryRequirements req;
  vkGetBufferMemoryRequirements(vk.device, buffer_, &req);
  VkMemoryPropertyFlags required = place == MemoryPlace::HostReadback
                                       ? VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT
                                       : VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT;
  VkMemoryPropertyFlags preferred =
      place == MemoryPlace::HostReadback ? required | VK_MEMORY_PROPERTY_HOST_CACHED_BIT : required;
  VkMemoryAllocateFlagsInfo flags{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_FLAGS_INFO};
  flags.flags = VK_MEMORY_ALLOCATE_DEVICE_ADDRESS_BIT;
  VkMemoryAllocateInfo ai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  ai.pNext = &flags;
  ai.allocationSize = req.size;
  ai.memoryTypeIndex = findMemoryType(vk.memoryProperties, req.memoryTypeBits, required, preferred);
  VkResult r = vkAllocateMemory(vk.device, &ai, nullptr, &memory_);
  if (r != VK_SUCCESS) {
    vkDestroyBuffer(vk.device, buffer_, nullptr);
    buffer_ = VK_NULL_HANDLE;
    throw GpuError("cannot allocate " + std::to_string(size >> 20) + " MiB of GPU memory (" + vkResultName(r) +
                   "): lower --spp or the panel size");
  }
  HT_VK(vkBindBufferMemory(vk.device, buffer_, memory_, 0));
  VkMemoryPropertyFlags got = vk.memoryProperties.memoryTypes[ai.memoryTypeIndex].propertyFlags;
  if ((got & VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT) && (got & VK_MEMORY_PROPERTY_HOST_COHERENT_BIT) &&
      (place == MemoryPlace::HostReadback || vk.mapDeviceMemory)) {
    HT_VK(vkMapMemory(vk.device, memory_, 0, VK_WHOLE_SIZE, 0, &mapped_));
  }
  VkBufferDeviceAddressInfo dai{VK_STRUCTURE_TYPE_BUFFER_DEVICE_ADDRESS_INFO};
  dai.buffer = buffer_;
  address_ = vkGetBufferDeviceAddress(vk.device, &dai);
}

DeviceBuffer::~DeviceBuffer() { release(); }

void DeviceBuffer::release() {
  if (!vk_) return;
  if (mapped_) vkUnmapMemory(vk_->device, memory_);
  if (buffer_) vkDestroyBuffer(vk_->device, buffer_, nullptr);
  if (memory_) vkFreeMemory(vk_->device, memory_, nullptr);
  vk_ = nullptr;
  buffer_ = VK_NULL_HANDLE;
  memory_ = VK_NULL_HANDLE;
  mapped_ = nullptr;
}

DeviceBuffer::DeviceBuffer(DeviceBuffer&& o) noexcept { *this = std::move(o); }

DeviceBuffer& DeviceBuffer::operator=(DeviceBuffer&& o) noexcept {
  if (this != &o) {
    release();
    vk_ = std::exchange(o.vk_, nullptr);
    buffer_ = std::exchange(o.buffer_, VK_NULL_HANDLE);
    memory_ = std::exchange(o.memory_, VK_NULL_HANDLE);
    address_ = std::exchange(o.address_, 0);
    size_ = std::exchange(o.size_, 0);
    mapped_ = std::exchange(o.mapped_, nullptr);
  }
  return *this;
}

void DeviceBuffer::upload(const void* data, VkDeviceSize bytes, VkDeviceSize offset) {
  StagingBuffer(*vk_).upload(*this, data, bytes, offset);
}

void DeviceBuffer::download(void* data, VkDeviceSize bytes, VkDeviceSize offset) const {
  StagingBuffer(*vk_).download(*this, data, bytes, offset);
}

DeviceBuffer& StagingBuffer::reserve(VkDeviceSize bytes) {
  if (buffer_.size() < bytes) {
    buffer_ = DeviceBuffer();  // the old one goes before the larger one is allocated
    buffer_ = DeviceBuffer(*vk_, bytes, MemoryPlace::HostReadback);
  }
  return buffer_;
}

void StagingBuffer::upload(DeviceBuffer& to, const void* data, VkDeviceSize bytes, VkDeviceSize offset) {
  if (bytes == 0) return;
  if (to.mapped()) {
    std::memcpy(static_cast<char*>(to.mapped()) + offset, data, bytes);
    return;
  }
  DeviceBuffer& staging = reserve(bytes);
  std::memcpy(staging.mapped(), data, bytes);
  OneShotCommands once(*vk_);
  const VkBufferCopy region{0, offset, bytes};
  vkCmdCopyBuffer(once.cmd(), staging.handle(), to.handle(), 1, &region);
  once.submitAndWait();
}

void StagingBuffer::download(const DeviceBuffer& from, void* data, VkDeviceSize bytes, VkDeviceSize offset) {
  if (bytes == 0) return;
  if (from.mapped()) {
    std::memcpy(data, static_cast<const char*>(from.mapped()) + offset, bytes);
    return;
  }
  DeviceBuffer& staging = reserve(bytes);
  OneShotCommands once(*vk_);
  const VkBufferCopy region{offset, 0, bytes};
  vkCmdCopyBuffer(once.cmd(), from.handle(), staging.handle(), 1, &region);
  once.submitAndWait();
  std::memcpy(data, staging.mapped(), bytes);
}

void UploadBatch::add(DeviceBuffer& buffer, const void* data, VkDeviceSize bytes, VkDeviceSize offset) {
  if (bytes == 0) return;
  copies_.push_back({&buffer, offset, bytes, staged_.size()});
  const auto* bytesIn = static_cast<const unsigned char*>(data);
  staged_.insert(staged_.end(), bytesIn, bytesIn + bytes);
}

void UploadBatch::submit() {
  // Host-visible buffers are written in place; the others are copied from the staging buffer in one submission.
  std::size_t unmapped = 0;
  for (const Copy& c : copies_) {
    if (!c.buffer->mapped()) {
      ++unmapped;
      continue;
    }
    std::memcpy(static_cast<unsigned char*>(c.buffer->mapped()) + c.offset, staged_.data() + c.stagingOffset, c.bytes);
  }
  if (unmapped > 0) {
    StagingBuffer own(vk_);  // when the batch was given none
    DeviceBuffer& staging = (staging_ ? *staging_ : own).reserve(staged_.size());
    std::memcpy(staging.mapped(), staged_.data(), staged_.size());
    OneShotCommands commands(vk_);
    for (const Copy& c : copies_) {
      if (c.buffer->mapped()) continue;
      const VkBufferCopy region{c.stagingOffset, c.offset, c.bytes};
      vkCmdCopyBuffer(commands.cmd(), staging.handle(), c.buffer->handle(), 1, &region);
    }
    commands.submitAndWait();
  }
  copies_.clear();
  staged_.clear();
}

OneShotCommands::OneShotCommands(VulkanContext::Impl& vk) : vk_(vk) {
  VkCommandBufferAllocateInfo ai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  ai.commandPool = vk.commandPool;
  ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  ai.commandBufferCount = 1;
  HT_VK(vkAllocateCommandBuffers(vk.device, &ai, &cmd_));
  VkFenceCreateInfo fci{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
  HT_VK(vkCreateFence(vk.device, &fci, nullptr, &fence_));
  VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  HT_VK(vkBeginCommandBuffer(cmd_, &bi));
}

OneShotCommands::~OneShotCommands() {
  vkDestroyFence(vk_.device, fence_, nullptr);
  vkFreeCommandBuffers(vk_.device, vk_.commandPool, 1, &cmd_);
}

void OneShotCommands::submitAndWait() {
  HT_VK(vkEndCommandBuffer(cmd_));
  VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  si.commandBufferCount = 1;
  si.pCommandBuffers = &cmd_;
  HT_VK(vkQueueSubmit(vk_.queue, 1, &si, fence_));
  HT_VK(vkWaitForFences(vk_.device, 1, &fence_, VK_TRUE, UINT64_MAX));
}

}  // namespace ht::gpu
