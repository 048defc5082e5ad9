// gpu_scene.h - a scene resident on the device: the BVH in the 64-byte node layout, shading records
// (vertices, normals, texcoords, triangles, materials, lights, textures). Built once, shared by every frame.
#pragma once
#include <cstdint>

#include "bvh/bvh_builder.h"
#include "bvh/gpu_layout.h"
#include "gpu/device_buffer.h"
#include "scene/scene.h"

namespace ht::gpu {

class GpuScene {
 public:
  GpuScene(VulkanContext::Impl& vk, const Scene& scene, const bvh::BuildOptions& options);
  // With the BVH of `scene` built beforehand (bvh::buildGpuBvh), e.g. on a thread that does not own the device.
  GpuScene(VulkanContext::Impl& vk, const Scene& scene, bvh::GpuBvh bvh);

  const bvh::BuildReport& bvhReport() const { return bvhReport_; }
  const SceneFeatures& features() const { return features_; }
  std::uint32_t lightCount() const { return lightCount_; }
  std::uint32_t textureCount() const { return textureCount_; }
  glm::vec3 background() const { return background_; }
  glm::vec3 ambient() const { return ambient_; }

  // Replaces the light records with `scene`'s (same count as at construction, else GpuError).
  void updateLights(const Scene& scene);

  DeviceBuffer nodes, bvhTriangles, vertices, normals, texcoords, triangles, materials, lights, textures, texels;
  bool hasNormals = false, hasTexcoords = false;

 private:
  bvh::BuildReport bvhReport_;
  SceneFeatures features_;
  std::uint32_t lightCount_ = 0, textureCount_ = 0;
  glm::vec3 background_{0.0f}, ambient_{0.0f};
};

}  // namespace ht::gpu
