// path_buffers.h - the device memory of the wavefront loop: the state of a batch of paths (rays, queues, hits,
// radiance, shadow slots) and the frame's outputs (subpixel values, the RGBA views read back). Both are kept across
// frames and reallocated only when a frame needs more; `generation` tells the descriptors when to rebind.
#pragma once
#include <algorithm>
#include <cstdint>

#include "gpu/device_buffer.h"
#include "gpu/vulkan_impl.h"

namespace ht::gpu {

// Path state for one batch of `capacity` paths; reallocated only when a frame needs more.
struct PathBuffers {
  std::uint32_t capacity = 0;
  std::uint32_t lightSlots = 0;  // shadow slots per path
  std::uint64_t generation = 0;  // bumped on every reallocation
  DeviceBuffer rays[2], queuePath[2], queueLeaves, hits, radiance, throughput, shadowRays, shadowContrib, shadowQueue;

  // Grows (never shrinks) to at least `paths` paths with `lights` shadow slots each.
  void ensure(VulkanContext::Impl& vk, std::uint32_t paths, std::uint32_t lights);
  // Device memory of one path with `lights` shadow slots (the batch-size budget).
  static std::uint64_t bytesPerPath(std::uint32_t lights);
};

// The frame's outputs, kept across frames of the same size (a daemon streams many) instead of reallocated.
struct OutputBuffers {
  std::uint32_t width = 0, height = 0;
  std::uint64_t generation = 0;  // bumped on every reallocation
  DeviceBuffer subpixels, image;

  void ensure(VulkanContext::Impl& vk, std::uint32_t w, std::uint32_t h);
};

}  // namespace ht::gpu
