// bvh_texel_views.cpp
#include "gpu/bvh_texel_views.h"

#include <algorithm>

namespace ht::gpu {

namespace {
constexpr VkDeviceSize kTexelBytes = 16;  // one RGBA32 texel
}

VkBufferView BvhTexelViews::makeView(const DeviceBuffer& buffer, VkFormat format) {
  const VkDeviceSize maxBytes = static_cast<VkDeviceSize>(vk_.info.maxTexelBufferElements) * kTexelBytes;
  const VkDeviceSize texelBytes = std::max<VkDeviceSize>(buffer.size() / kTexelBytes * kTexelBytes, kTexelBytes);
  if (texelBytes > maxBytes) covers_ = false;
  VkBufferViewCreateInfo ci{VK_STRUCTURE_TYPE_BUFFER_VIEW_CREATE_INFO};
  ci.buffer = buffer.handle();
  ci.format = format;
  ci.offset = 0;
  ci.range = std::min(texelBytes, maxBytes);
  VkBufferView view = VK_NULL_HANDLE;
  HT_VK(vkCreateBufferView(vk_.device, &ci, nullptr, &view));
  return view;
}

BvhTexelViews::BvhTexelViews(VulkanContext::Impl& vk, VkDescriptorSetLayout layout, const DeviceBuffer& nodes,
                             const DeviceBuffer& triangles)
    : vk_(vk) {
  views_[0] = makeView(nodes, VK_FORMAT_R32G32B32A32_SFLOAT);
  views_[1] = makeView(nodes, VK_FORMAT_R32G32B32A32_UINT);
  views_[2] = makeView(triangles, VK_FORMAT_R32G32B32A32_SFLOAT);
  views_[3] = makeView(triangles, VK_FORMAT_R32G32B32A32_UINT);

  VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER, 4};
  VkDescriptorPoolCreateInfo pci{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  pci.maxSets = 1;
  pci.poolSizeCount = 1;
  pci.pPoolSizes = &size;
  HT_VK(vkCreateDescriptorPool(vk.device, &pci, nullptr, &pool_));
  VkDescriptorSetAllocateInfo ai{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
  ai.descriptorPool = pool_;
  ai.descriptorSetCount = 1;
  ai.pSetLayouts = &layout;
  HT_VK(vkAllocateDescriptorSets(vk.device, &ai, &set_));
  VkWriteDescriptorSet writes[4];
  for (std::uint32_t b = 0; b < 4; ++b) {
    writes[b] = {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    writes[b].dstSet = set_;
    writes[b].dstBinding = b;
    writes[b].descriptorCount = 1;
    writes[b].descriptorType = VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER;
    writes[b].pTexelBufferView = &views_[b];
  }
  vkUpdateDescriptorSets(vk.device, 4, writes, 0, nullptr);
}

BvhTexelViews::~BvhTexelViews() {
  vkDestroyDescriptorPool(vk_.device, pool_, nullptr);
  for (VkBufferView v : views_) vkDestroyBufferView(vk_.device, v, nullptr);
}

}  // namespace ht::gpu
