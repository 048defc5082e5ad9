// leak_count.h - how many rays from inside a closed mesh miss it, per tracer: holotrace's CPU reference
// (bvh/cpu_traversal.h, the shared kernel code), the GPU kernel (gpu::Renderer::traceClosest), robust
// Embree 3 and the naive Möller-Trumbore controls. Every miss is a leak.
#pragma once
#include <cstdint>
#include <span>

#include "bvh/ray_types.h"
#include "test_meshes.h"

namespace ht::gpu {
class VulkanContext;
}

namespace ht::accuracy {

struct LeakCounts {
  uint64_t rays = 0;
  uint64_t cpuMisses = 0, cpuOverflows = 0;
  uint64_t gpuMisses = 0;  // valid when gpuRun
  bool gpuRun = false;
  uint64_t embreeMisses = 0, mtEpsilonMisses = 0, mtNoEpsilonMisses = 0;  // valid when anchorsRun
  bool anchorsRun = false;
  uint64_t trianglesDropped = 0;  // by holotrace's builder (placement can collapse vertices)
};

struct LeakOptions {
  gpu::VulkanContext* gpu = nullptr;  // null: no GPU run
  bool anchors = true;                // Embree and the Möller-Trumbore controls
};

LeakCounts countLeaks(const TestMesh& mesh, std::span<const gpu_shared::HtRay> rays, const LeakOptions& options);

}  // namespace ht::accuracy
