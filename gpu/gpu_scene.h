// gpu_scene.h - a scene resident on the device: the BVH in the 64-byte node layout (flattened, or the bottom levels,
// top level and instance table of a two-level BVH, scene_bvh.h), shading records (vertices, normals, texcoords,
// triangles, materials, lights, textures). Built once, shared by every frame; a two-level scene takes node moves in
// place (moveInstances).
#pragma once
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "bvh/bvh_builder.h"
#include "bvh/gpu_layout.h"
#include "gpu/device_buffer.h"
#include "gpu/scene_bvh.h"
#include "gpu/wavefront_types.h"
#include "scene/scene.h"

namespace ht::gpu {

// The device records of `scene`'s punctual lights, in scene order (SceneError over HT_MAX_LIGHTS).
std::vector<gpu_shared::GpuLight> packLights(const Scene& scene);

class GpuScene {
 public:
  GpuScene(VulkanContext::Impl& vk, const Scene& scene, const bvh::BuildOptions& options);
  // With the BVH of `scene` built beforehand (bvh::buildGpuBvh), e.g. on a thread that does not own the device.
  GpuScene(VulkanContext::Impl& vk, const Scene& scene, bvh::GpuBvh bvh);
  GpuScene(VulkanContext::Impl& vk, const Scene& scene, SceneBvh bvh);

  const bvh::BuildReport& bvhReport() const { return bvhReport_; }
  const SceneFeatures& features() const { return features_; }
  std::uint32_t lightCount() const { return lightCount_; }
  std::uint32_t textureCount() const { return textureCount_; }
  glm::vec3 background() const { return background_; }
  glm::vec3 ambient() const { return ambient_; }

  // Replaces the light records with `scene`'s (same count as at construction, else GpuError). Returns the lights
  // whose shadow rays changed (bit l: light l's type, position or direction differs), so that occlusion recorded for
  // the others still holds (gpu/frame_reuse.h).
  std::uint32_t updateLights(const Scene& scene);

  bvh::BvhLayout layout() const { return layout_; }
  const bvh::TwoLevelBvh* twoLevel() const { return twoLevel_.get(); }
  // Two-level layout only: `scene` is this scene with the given instances (Scene::instances() indices) moved
  // (setNodeWorldMatrix). Refits their bottom levels, rebuilds the top level and uploads only what changed: the moved
  // instances' node and triangle slots, the top level, the instance table and their vertex, normal and triangle
  // records. Returns true when a buffer had to be reallocated (its descriptors must be rebuilt). The caller makes
  // sure no frame in flight reads the buffers.
  bool moveInstances(const Scene& scene, std::span<const std::uint32_t> moved);
  double lastUploadMs() const { return lastUploadMs_; }  // of the last moveInstances

  DeviceBuffer nodes, bvhTriangles, vertices, normals, texcoords, triangles, materials, lights, textures, texels;
  DeviceBuffer topNodes, instances;  // two-level BVH; a dummy entry with the flattened one
  bool hasNormals = false, hasTexcoords = false;

 private:
  void uploadRecords(const Scene& scene);
  // Uploads the two-level BVH's top level and instance table (through `batch` when given), reallocating a buffer that
  // is too small; true then.
  bool uploadTopLevel(UploadBatch* batch = nullptr);
  void uploadInstanceRecords(const Scene& scene, const SceneInstance& instance, std::size_t index, UploadBatch& batch);
  VulkanContext::Impl* vk_;
  StagingBuffer moveStaging_;  // the uploads of node moves (moveInstances), reused from move to move
  bvh::BvhLayout layout_ = bvh::BvhLayout::Flattened;
  std::unique_ptr<bvh::TwoLevelBvh> twoLevel_;
  double lastUploadMs_ = 0.0;
  bvh::BuildReport bvhReport_;
  SceneFeatures features_;
  std::uint32_t lightCount_ = 0, textureCount_ = 0;
  std::vector<gpu_shared::GpuLight> lightRecords_;  // as uploaded
  glm::vec3 background_{0.0f}, ambient_{0.0f};
};

}  // namespace ht::gpu
