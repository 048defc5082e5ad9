// vulkan_handles.h - the raw Vulkan objects of a VulkanContext, for code outside gpu/ that records its own commands on
// the same device (the display sink, present/). The context keeps owning them; the queue is externally synchronised
// (one thread submits to it at a time), so a caller that submits uses a context of its own.
#pragma once
#include <vulkan/vulkan.h>

#include <cstdint>

#include "gpu/vulkan_context.h"

namespace ht::gpu {

struct VulkanHandles {
  VkInstance instance = VK_NULL_HANDLE;
  VkPhysicalDevice physical = VK_NULL_HANDLE;
  VkDevice device = VK_NULL_HANDLE;
  VkQueue queue = VK_NULL_HANDLE;
  std::uint32_t queueFamily = 0;
  VkCommandPool commandPool = VK_NULL_HANDLE;  // RESET_COMMAND_BUFFER pool of queueFamily
};

VulkanHandles vulkanHandles(VulkanContext& context);

// Throws GpuError naming `call` and the VkResult unless `result` is VK_SUCCESS.
void checkVulkan(VkResult result, const char* call);

}  // namespace ht::gpu
