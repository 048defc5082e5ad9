// gpu_scene.cpp - packs a Scene into the GPU records of gpu/wavefront_types.h and uploads them.
#include "gpu/gpu_scene.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "common/error.h"
#include "gpu/convex_parts.h"
#include "gpu/wavefront_types.h"

namespace ht::gpu {

namespace {

template <typename T>
DeviceBuffer uploadVector(VulkanContext::Impl& vk, const std::vector<T>& data) {
  DeviceBuffer buffer(vk, std::max<VkDeviceSize>(sizeof(T) * data.size(), 16), MemoryPlace::Device);
  buffer.upload(data.data(), sizeof(T) * data.size());
  return buffer;
}

std::vector<gpu_shared::GpuMaterial> packMaterials(const Scene& scene) {
  std::vector<gpu_shared::GpuMaterial> out;
  for (const Material& m : scene.materials) {
    gpu_shared::GpuMaterial g{};
    g.baseColor = glm::vec4(m.baseColor, static_cast<float>(m.baseColorTexture));
    g.emissive = glm::vec4(m.emissive, static_cast<float>(static_cast<std::uint32_t>(m.kind())));
    g.params = glm::vec4(m.metallic, m.roughness, m.transmission, m.ior);
    out.push_back(g);
  }
  if (out.empty())
    out.push_back({glm::vec4(0.8f, 0.8f, 0.8f, -1.0f), glm::vec4(0.0f), glm::vec4(0.0f, 1.0f, 0.0f, 1.5f)});
  return out;
}

// The shading record of triangle t: its corners and material (checked).
glm::uvec4 triangleRecord(const Scene& scene, size_t t) {
  std::uint32_t material = t < scene.triangleMaterial.size() ? scene.triangleMaterial[t] : 0u;
  if (material >= std::max<size_t>(scene.materials.size(), 1)) {
    throw SceneError(scene.name, "triangle " + std::to_string(t) + " uses material " + std::to_string(material) +
                                     " but the scene has " + std::to_string(scene.materials.size()));
  }
  return glm::uvec4(scene.triangles[t], material);
}

}  // namespace

std::vector<gpu_shared::GpuLight> packLights(const Scene& scene) {
  std::vector<gpu_shared::GpuLight> out;
  for (const Light& l : scene.lights) {
    gpu_shared::GpuLight g{};
    g.position = glm::vec4(l.position, static_cast<float>(static_cast<std::uint32_t>(l.type)));
    glm::vec3 dir = glm::length(l.direction) > 0.0f ? glm::normalize(l.direction) : glm::vec3(0.0f, -1.0f, 0.0f);
    g.direction = glm::vec4(dir, l.range);
    g.radiance = glm::vec4(l.color * l.intensity, 0.0f);
    g.cone = glm::vec4(std::cos(l.outerConeAngle), std::cos(l.innerConeAngle), 0.0f, 0.0f);
    out.push_back(g);
  }
  if (out.size() > gpu_shared::HT_MAX_LIGHTS) {
    throw SceneError(scene.name, std::to_string(out.size()) + " punctual lights; holotrace traces at most " +
                                     std::to_string(gpu_shared::HT_MAX_LIGHTS) + " (remove or merge lights)");
  }
  return out;
}

GpuScene::GpuScene(VulkanContext::Impl& vk, const Scene& scene, const bvh::BuildOptions& options)
    : GpuScene(vk, scene, buildSceneBvh(scene, options, BvhLayoutPolicy::Automatic)) {}

GpuScene::GpuScene(VulkanContext::Impl& vk, const Scene& scene, bvh::GpuBvh bvh)
    : GpuScene(vk, scene, flattenedSceneBvh(std::move(bvh))) {}

GpuScene::GpuScene(VulkanContext::Impl& vk, const Scene& scene, SceneBvh bvh) : vk_(&vk), moveStaging_(vk) {
  features_ = scene.features();
  background_ = scene.background;
  ambient_ = scene.ambient;
  bvhReport_ = bvh.report;
  layout_ = bvh.layout;
  if (layout_ == bvh::BvhLayout::TwoLevel) {
    twoLevel_ = std::move(bvh.twoLevel);
    nodes = uploadVector(vk, twoLevel_->blasNodes());
    bvhTriangles = uploadVector(vk, twoLevel_->blasTriangles());
    // Room for every top level over these instances (at most one inner node per instance, plus the root of a
    // single leaf), so a move never reallocates them.
    const size_t count = twoLevel_->instanceCount();
    topNodes = DeviceBuffer(vk, (count + 1) * sizeof(gpu_shared::GpuBvhNode), MemoryPlace::Device);
    instances = DeviceBuffer(vk, std::max<size_t>(count, 1) * sizeof(glm::uvec4), MemoryPlace::Device);
    uploadTopLevel();
  } else {
    tagConvexParts(bvh.flattened, scene);  // (the two-level walk skips a convex part's instance instead)
    nodes = uploadVector(vk, bvh.flattened.nodes);
    bvhTriangles = uploadVector(vk, bvh.flattened.triangles);
    topNodes = uploadVector(vk, std::vector<gpu_shared::GpuBvhNode>(1));  // never read
    instances = uploadVector(vk, std::vector<glm::uvec4>(1));
  }
  uploadRecords(scene);
}

void GpuScene::uploadRecords(const Scene& scene) {
  VulkanContext::Impl& vk = *vk_;
  std::vector<glm::vec4> positions;
  positions.reserve(scene.positions.size());
  const std::vector<float> tags = convexVertexTags(scene);  // .w: the convex part tag (gpu/convex_parts.h)
  for (std::size_t v = 0; v < scene.positions.size(); ++v) positions.emplace_back(scene.positions[v], tags[v]);
  vertices = uploadVector(vk, positions);

  hasNormals = !scene.normals.empty() && scene.normals.size() == scene.positions.size();
  std::vector<glm::vec4> normalData;
  if (hasNormals) {
    for (const glm::vec3& n : scene.normals) normalData.emplace_back(n, 0.0f);
  }
  normals = uploadVector(vk, normalData);

  hasTexcoords = !scene.texcoords.empty() && scene.texcoords.size() == scene.positions.size();
  texcoords = uploadVector(vk, hasTexcoords ? scene.texcoords : std::vector<glm::vec2>{});

  std::vector<glm::uvec4> tris;
  tris.reserve(scene.triangles.size());
  for (size_t t = 0; t < scene.triangles.size(); ++t) tris.push_back(triangleRecord(scene, t));
  triangles = uploadVector(vk, tris);
  materials = uploadVector(vk, packMaterials(scene));
  std::vector<gpu_shared::GpuLight> lightData = packLights(scene);
  lightCount_ = static_cast<std::uint32_t>(lightData.size());
  lights = uploadVector(vk, lightData);
  lightRecords_ = std::move(lightData);

  std::vector<gpu_shared::GpuTexture> directory;
  std::vector<glm::vec4> texelData;
  for (const Texture& t : scene.textures) {
    directory.push_back({glm::uvec4(static_cast<std::uint32_t>(texelData.size()), t.width, t.height, 0u)});
    texelData.insert(texelData.end(), t.texels.begin(), t.texels.end());
  }
  textureCount_ = static_cast<std::uint32_t>(directory.size());
  textures = uploadVector(vk, directory);
  texels = uploadVector(vk, texelData);
}

bool GpuScene::uploadTopLevel(UploadBatch* batch) {
  bool reallocated = false;
  const auto put = [&](DeviceBuffer& buffer, const void* data, VkDeviceSize bytes) {
    if (buffer.size() < bytes) {
      buffer = DeviceBuffer(*vk_, bytes, MemoryPlace::Device);
      reallocated = true;
    }
    if (batch)
      batch->add(buffer, data, bytes);
    else
      buffer.upload(data, bytes);
  };
  put(topNodes, twoLevel_->topNodes().data(), twoLevel_->topNodes().size() * sizeof(gpu_shared::GpuBvhNode));
  put(instances, twoLevel_->instanceTable().data(), twoLevel_->instanceTable().size() * sizeof(glm::uvec4));
  return reallocated;
}

void GpuScene::uploadInstanceRecords(const Scene& scene, const SceneInstance& instance, std::size_t index,
                                     UploadBatch& batch) {
  if (instance.triangleCount == 0) return;
  const size_t first = instance.firstTriangle, end = first + instance.triangleCount;
  std::vector<glm::uvec4> tris;
  tris.reserve(instance.triangleCount);
  std::uint32_t lo = ~0u, hi = 0;
  for (size_t t = first; t < end; ++t) {
    tris.push_back(triangleRecord(scene, t));
    for (int c = 0; c < 3; ++c) {
      lo = std::min(lo, scene.triangles[t][c]);
      hi = std::max(hi, scene.triangles[t][c]);
    }
  }
  batch.add(triangles, tris.data(), tris.size() * sizeof(glm::uvec4), first * sizeof(glm::uvec4));
  // The node's vertices: the span its triangles index (a node's vertices are contiguous in a loaded scene).
  std::vector<glm::vec4> values;
  values.reserve(hi - lo + 1);
  const float tag =
      instance.node < 0 ? 0.0f : convexVertexTag(scene.nodes[static_cast<std::size_t>(instance.node)], index);
  for (std::uint32_t v = lo; v <= hi; ++v) values.emplace_back(scene.positions[v], tag);
  batch.add(vertices, values.data(), values.size() * sizeof(glm::vec4), lo * sizeof(glm::vec4));
  if (!hasNormals) return;
  values.clear();
  for (std::uint32_t v = lo; v <= hi; ++v) values.emplace_back(scene.normals[v], 0.0f);
  batch.add(normals, values.data(), values.size() * sizeof(glm::vec4), lo * sizeof(glm::vec4));
}

bool GpuScene::moveInstances(const Scene& scene, std::span<const std::uint32_t> moved) {
  if (!twoLevel_)
    throw GpuError("moveInstances: this scene is traced with the flattened BVH (use Renderer::moveNodes)");
  const std::vector<SceneInstance> sceneInstances = scene.instances();
  for (std::uint32_t i : moved) {
    if (i >= sceneInstances.size() || i >= twoLevel_->instanceCount()) {
      throw GpuError("moveInstances: no instance " + std::to_string(i) + " (the scene has " +
                     std::to_string(twoLevel_->instanceCount()) + ")");
    }
  }
  twoLevel_->updateInstances(scene.positions, scene.triangles, moved);
  bool reallocated = false;
  UploadBatch batch(*vk_, &moveStaging_);  // one staging buffer, kept, and one submission for every range below
  const auto& blasNodes = twoLevel_->blasNodes();
  const auto& blasTris = twoLevel_->blasTriangles();
  constexpr VkDeviceSize kNode = sizeof(gpu_shared::GpuBvhNode);
  constexpr VkDeviceSize kSlot = sizeof(glm::vec4) * gpu_shared::HT_TRI_STRIDE;
  if (twoLevel_->lastUpdateRelaidOut()) {  // every range may have moved
    if (nodes.size() < blasNodes.size() * kNode || bvhTriangles.size() < blasTris.size() * sizeof(glm::vec4)) {
      nodes = uploadVector(*vk_, blasNodes);
      bvhTriangles = uploadVector(*vk_, blasTris);
      reallocated = true;
    } else {
      batch.add(nodes, blasNodes.data(), blasNodes.size() * kNode);
      batch.add(bvhTriangles, blasTris.data(), blasTris.size() * sizeof(glm::vec4));
    }
  } else {
    for (std::uint32_t i : moved) {
      const bvh::InstanceSlots r = twoLevel_->instanceSlots(i);
      batch.add(nodes, blasNodes.data() + r.nodeBase, r.nodeCount * kNode, r.nodeBase * kNode);
      batch.add(bvhTriangles, blasTris.data() + size_t{r.slotBase} * gpu_shared::HT_TRI_STRIDE, r.slotCount * kSlot,
                r.slotBase * kSlot);
    }
  }
  const auto start = std::chrono::steady_clock::now();
  reallocated |= uploadTopLevel(&batch);
  for (std::uint32_t i : moved) uploadInstanceRecords(scene, sceneInstances[i], i, batch);
  batch.submit();
  lastUploadMs_ = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return reallocated;
}

std::uint32_t GpuScene::updateLights(const Scene& scene) {
  std::vector<gpu_shared::GpuLight> lightData = packLights(scene);
  if (lightData.size() != lightCount_) {
    throw GpuError("updateLights: the scene has " + std::to_string(lightData.size()) + " lights, the device scene " +
                   std::to_string(lightCount_) + " (a changed light count needs Renderer::replaceScene)");
  }
  lights.upload(lightData.data(), sizeof(gpu_shared::GpuLight) * lightData.size());
  // A shadow ray runs from the surface point to the light's position, or against its direction (shade.comp
  // light_incidence): colour, intensity, range and cone change only what it carries.
  std::uint32_t raysChanged = 0;
  for (std::size_t l = 0; l < lightData.size(); ++l) {
    const gpu_shared::GpuLight &before = lightRecords_[l], &after = lightData[l];
    if (before.position != after.position || glm::vec3(before.direction) != glm::vec3(after.direction)) {
      raysChanged |= 1u << l;
    }
  }
  lightRecords_ = std::move(lightData);
  return raysChanged;
}

}  // namespace ht::gpu
