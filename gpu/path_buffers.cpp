// path_buffers.cpp - see path_buffers.h.
#include "gpu/path_buffers.h"

#include "bvh/ray_types.h"

namespace ht::gpu {

void PathBuffers::ensure(VulkanContext::Impl& vk, std::uint32_t paths, std::uint32_t lights) {
  std::uint32_t slots = std::max(lights, 1u);
  if (paths <= capacity && slots <= lightSlots) return;
  capacity = std::max(paths, capacity);
  lightSlots = std::max(slots, lightSlots);
  ++generation;
  VkDeviceSize n = capacity, s = static_cast<VkDeviceSize>(capacity) * lightSlots;
  for (int q = 0; q < 2; ++q) {
    rays[q] = DeviceBuffer(vk, n * sizeof(gpu_shared::HtRay), MemoryPlace::Device);
    queuePath[q] = DeviceBuffer(vk, n * 4, MemoryPlace::Device);
  }
  queueLeaves = DeviceBuffer(vk, 2 * n * 4, MemoryPlace::Device);  // both queues' (shader_interface.h)
  hits = DeviceBuffer(vk, n * sizeof(gpu_shared::HtHit), MemoryPlace::Device);
  radiance = DeviceBuffer(vk, n * 16, MemoryPlace::Device);
  throughput = DeviceBuffer(vk, n * 16, MemoryPlace::Device);
  shadowRays = DeviceBuffer(vk, s * sizeof(gpu_shared::HtRay), MemoryPlace::Device);
  shadowContrib = DeviceBuffer(vk, s * 16, MemoryPlace::Device);
  shadowQueue = DeviceBuffer(vk, s * 8, MemoryPlace::Device);  // slot, convex part left (shade.comp)
}

std::uint64_t PathBuffers::bytesPerPath(std::uint32_t lights) {
  return 2 * (sizeof(gpu_shared::HtRay) + 4 + 4) + sizeof(gpu_shared::HtHit) + 32 +
         std::max(lights, 1u) * (sizeof(gpu_shared::HtRay) + 16 + 8);
}

void OutputBuffers::ensure(VulkanContext::Impl& vk, std::uint32_t w, std::uint32_t h) {
  if (w == width && h == height) return;
  subpixels = DeviceBuffer(vk, static_cast<VkDeviceSize>(w) * h * 3 * sizeof(float), MemoryPlace::Device);
  image = DeviceBuffer(vk, static_cast<VkDeviceSize>(w) * h * 16, MemoryPlace::HostReadback);
  width = w;
  height = h;
  ++generation;
}

}  // namespace ht::gpu
