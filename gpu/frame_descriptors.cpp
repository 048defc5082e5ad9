// frame_descriptors.cpp
#include "gpu/frame_descriptors.h"

#include <algorithm>
#include <vector>

namespace ht::gpu {

namespace {

VkDeviceSize texelSize(VkFormat format) {
  switch (format) {
    case VK_FORMAT_R32_UINT:
    case VK_FORMAT_R32_SFLOAT: return 4;
    case VK_FORMAT_R32G32_SFLOAT: return 8;
    default: return 16;
  }
}

}  // namespace

VkDescriptorType FrameDescriptors::bindingType(std::uint32_t binding) {
  using namespace gpu_shared;
  if (binding == HT_BINDING_FRAME) return VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
  if ((binding >= HT_BINDING_STORAGE_FIRST && binding <= HT_BINDING_STORAGE_LAST) || binding == HT_BINDING_ACCUM_SUMS ||
      binding == HT_BINDING_ACCUM_HALVES || binding == HT_BINDING_QUEUE_LEAVES)
    return VK_DESCRIPTOR_TYPE_STORAGE_TEXEL_BUFFER;
  return VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER;
}

FrameDescriptors::FrameDescriptors(VulkanContext::Impl& vk, VkDescriptorSetLayout layout) : vk_(vk) {
  VkDescriptorPoolSize sizes[] = {{VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER, gpu_shared::HT_BINDING_COUNT},
                                  {VK_DESCRIPTOR_TYPE_STORAGE_TEXEL_BUFFER, gpu_shared::HT_BINDING_COUNT},
                                  {VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1}};
  VkDescriptorPoolCreateInfo pci{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  pci.maxSets = 1;
  pci.poolSizeCount = 3;
  pci.pPoolSizes = sizes;
  HT_VK(vkCreateDescriptorPool(vk.device, &pci, nullptr, &pool_));
  VkDescriptorSetAllocateInfo ai{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
  ai.descriptorPool = pool_;
  ai.descriptorSetCount = 1;
  ai.pSetLayouts = &layout;
  HT_VK(vkAllocateDescriptorSets(vk.device, &ai, &set_));
}

FrameDescriptors::~FrameDescriptors() {
  vkDestroyDescriptorPool(vk_.device, pool_, nullptr);
  for (const Binding& b : bindings_) {
    if (b.view) vkDestroyBufferView(vk_.device, b.view, nullptr);
  }
}

bool FrameDescriptors::setView(std::uint32_t binding, const DeviceBuffer& buffer, VkFormat format, bool fresh) {
  Binding& b = bindings_[binding];
  const VkDeviceSize unit = texelSize(format);
  const VkDeviceSize maxBytes = static_cast<VkDeviceSize>(vk_.info.maxTexelBufferElements) * unit;
  const VkDeviceSize whole = std::max<VkDeviceSize>(buffer.size() / unit * unit, unit);
  if (!fresh && b.buffer == buffer.handle() && b.format == format && b.view) return whole <= maxBytes;
  if (b.view) vkDestroyBufferView(vk_.device, b.view, nullptr);
  VkBufferViewCreateInfo ci{VK_STRUCTURE_TYPE_BUFFER_VIEW_CREATE_INFO};
  ci.buffer = buffer.handle();
  ci.format = format;
  ci.range = std::min(whole, maxBytes);
  HT_VK(vkCreateBufferView(vk_.device, &ci, nullptr, &b.view));
  b.buffer = buffer.handle();
  b.format = format;
  b.range = ci.range;
  b.dirty = true;
  return whole <= maxBytes;
}

bool FrameDescriptors::setUniformTexels(std::uint32_t binding, const DeviceBuffer& buffer, VkFormat format,
                                        bool fresh) {
  return setView(binding, buffer, format, fresh);
}

void FrameDescriptors::setStorageTexels(std::uint32_t binding, const DeviceBuffer& buffer, VkFormat format,
                                        bool fresh) {
  if (!setView(binding, buffer, format, fresh)) {
    throw GpuError("a " + std::to_string(buffer.size() >> 20) + " MiB working buffer exceeds the device's " +
                   std::to_string(vk_.info.maxTexelBufferElements) +
                   " texel-buffer elements: lower the panel size or spp");
  }
}

void FrameDescriptors::setUniformBuffer(std::uint32_t binding, const DeviceBuffer& buffer) {
  Binding& b = bindings_[binding];
  if (b.buffer == buffer.handle()) return;
  b.buffer = buffer.handle();
  b.range = buffer.size();
  b.dirty = true;
}

void FrameDescriptors::flush() {
  std::vector<VkWriteDescriptorSet> writes;
  std::vector<VkDescriptorBufferInfo> infos;
  infos.reserve(bindings_.size());
  for (std::uint32_t i = 0; i < bindings_.size(); ++i) {
    Binding& b = bindings_[i];
    if (!b.dirty) continue;
    VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    w.dstSet = set_;
    w.dstBinding = i;
    w.descriptorCount = 1;
    w.descriptorType = bindingType(i);
    if (w.descriptorType == VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER) {
      infos.push_back({b.buffer, 0, b.range});
      w.pBufferInfo = &infos.back();
    } else {
      w.pTexelBufferView = &b.view;
    }
    writes.push_back(w);
    b.dirty = false;
  }
  if (!writes.empty())
    vkUpdateDescriptorSets(vk_.device, static_cast<std::uint32_t>(writes.size()), writes.data(), 0, nullptr);
}

}  // namespace ht::gpu
