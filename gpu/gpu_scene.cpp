// gpu_scene.cpp - packs a Scene into the GPU records of gpu/wavefront_types.h and uploads them.
#include "gpu/gpu_scene.h"

#include <cmath>
#include <string>
#include <vector>

#include "common/error.h"
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

}  // namespace

GpuScene::GpuScene(VulkanContext::Impl& vk, const Scene& scene, const bvh::BuildOptions& options) {
  features_ = scene.features();
  background_ = scene.background;
  ambient_ = scene.ambient;

  bvh::GpuBvh bvh = bvh::buildGpuBvh(scene.positions, scene.triangles, options);
  bvhReport_ = bvh.report;
  nodes = uploadVector(vk, bvh.nodes);
  bvhTriangles = uploadVector(vk, bvh.triangles);

  std::vector<glm::vec4> positions;
  positions.reserve(scene.positions.size());
  for (const glm::vec3& p : scene.positions) positions.emplace_back(p, 1.0f);
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
  for (size_t t = 0; t < scene.triangles.size(); ++t) {
    std::uint32_t material = t < scene.triangleMaterial.size() ? scene.triangleMaterial[t] : 0u;
    if (material >= std::max<size_t>(scene.materials.size(), 1)) {
      throw SceneError(scene.name, "triangle " + std::to_string(t) + " uses material " + std::to_string(material) +
                                       " but the scene has " + std::to_string(scene.materials.size()));
    }
    tris.emplace_back(scene.triangles[t], material);
  }
  triangles = uploadVector(vk, tris);
  materials = uploadVector(vk, packMaterials(scene));
  std::vector<gpu_shared::GpuLight> lightData = packLights(scene);
  lightCount_ = static_cast<std::uint32_t>(lightData.size());
  lights = uploadVector(vk, lightData);

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

void GpuScene::updateLights(const Scene& scene) {
  const std::vector<gpu_shared::GpuLight> lightData = packLights(scene);
  if (lightData.size() != lightCount_) {
    throw GpuError("updateLights: the scene has " + std::to_string(lightData.size()) + " lights, the device scene " +
                   std::to_string(lightCount_) + " (a changed light count needs Renderer::replaceScene)");
  }
  lights.upload(lightData.data(), sizeof(gpu_shared::GpuLight) * lightData.size());
}

}  // namespace ht::gpu
