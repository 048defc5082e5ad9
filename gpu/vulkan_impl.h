// vulkan_impl.h - internals of VulkanContext shared by the gpu/ sources (not a public header).
#pragma once
#include <vulkan/vulkan.h>

#include <atomic>
#include <memory>
#include <string>

#include "common/error.h"
#include "gpu/spirv_exact_float.h"
#include "gpu/vulkan_context.h"

namespace ht::gpu {

// Throws GpuError naming the failed call and the VkResult.
void checkVk(VkResult result, const char* call);
#define HT_VK(call) ::ht::gpu::checkVk((call), #call)
const char* vkResultName(VkResult result);

class PipelineLibrary;

struct VulkanContext::Impl {
  VkInstance instance = VK_NULL_HANDLE;
  VkDebugUtilsMessengerEXT messenger = VK_NULL_HANDLE;
  VkPhysicalDevice physical = VK_NULL_HANDLE;
  VkDevice device = VK_NULL_HANDLE;
  VkQueue queue = VK_NULL_HANDLE;
  uint32_t queueFamily = 0;
  VkCommandPool commandPool = VK_NULL_HANDLE;
  VkPhysicalDeviceMemoryProperties memoryProperties{};
  DeviceInfo info;
  ExactFloatOptions exactFloat;  // how shader modules are made exact (Options::fusedFloatMath, DeviceInfo)
  bool mapDeviceMemory = true;   // Options::mapDeviceMemory
  std::atomic<uint32_t> validationMessages{0};
  std::string lastValidationMessage;
  std::unique_ptr<PipelineLibrary> pipelines;  // created with the device, destroyed before it (vulkan_context.cpp)
};

}  // namespace ht::gpu
