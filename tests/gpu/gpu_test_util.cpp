#include "gpu_test_util.h"

#include <cmath>
#include <filesystem>
#include <map>

#include "camera_models/pinhole_model.h"

namespace ht::test {

gpu::VulkanContext& sharedContext() {
  static gpu::VulkanContext context(gpu::VulkanContext::Options{});
  return context;
}

gpu_shared::PinholeParams lookAt(glm::vec3 eye, glm::vec3 target, float fovyDeg, std::uint32_t w, std::uint32_t h) {
  glm::vec3 back = glm::normalize(eye - target);
  glm::vec3 right = glm::normalize(glm::cross(glm::vec3(0.0f, 1.0f, 0.0f), back));
  glm::vec3 up = glm::cross(back, right);
  gpu_shared::PinholeParams p{};
  p.cameraToWorld = glm::mat4(glm::vec4(right, 0.0f), glm::vec4(up, 0.0f), glm::vec4(back, 0.0f), glm::vec4(eye, 1.0f));
  p.lens = glm::vec4(std::tan(glm::radians(fovyDeg) * 0.5f), static_cast<float>(w) / static_cast<float>(h),
                     static_cast<float>(w), static_cast<float>(h));
  return p;
}

std::vector<gpu_shared::HtRay> pinholeRays(const gpu_shared::PinholeParams& p) {
  const auto w = static_cast<std::uint32_t>(p.lens.z), h = static_cast<std::uint32_t>(p.lens.w);
  std::vector<gpu_shared::HtRay> rays;
  rays.reserve(static_cast<size_t>(w) * h);
  for (std::uint32_t y = 0; y < h; ++y) {
    for (std::uint32_t x = 0; x < w; ++x) {
      glm::vec3 o, d;
      gpu_shared::pinhole_ray(p, x, y, glm::vec2(0.5f), o, d);
      rays.push_back({o, 0.0f, d, 3.0e38f});
    }
  }
  return rays;
}

DiffuseMirrorGlass addDiffuseMirrorGlass(Scene& s) {
  Material diffuse;
  diffuse.baseColor = glm::vec3(0.7f, 0.5f, 0.3f);
  Material mirror;
  mirror.metallic = 1.0f;
  mirror.roughness = 0.0f;
  Material glass;
  glass.transmission = 1.0f;
  glass.ior = 1.5f;
  const std::uint32_t d = test::addMaterial(s, diffuse), m = test::addMaterial(s, mirror);
  return {d, m, test::addMaterial(s, glass)};
}

std::uint32_t addMaterial(Scene& s, const Material& m) {
  s.materials.push_back(m);
  return static_cast<std::uint32_t>(s.materials.size() - 1);
}

void addQuad(Scene& s, glm::vec3 corner, glm::vec3 edgeU, glm::vec3 edgeV, std::uint32_t material) {
  auto base = static_cast<std::uint32_t>(s.positions.size());
  s.positions.insert(s.positions.end(), {corner, corner + edgeU, corner + edgeU + edgeV, corner + edgeV});
  s.triangles.push_back({base, base + 1, base + 2});
  s.triangles.push_back({base, base + 2, base + 3});
  s.triangleMaterial.insert(s.triangleMaterial.end(), {material, material});
}

// Icosahedron subdivided `subdivisions` times, vertices projected onto the sphere (outward winding).
void addIcosphere(Scene& s, glm::vec3 center, float radius, int subdivisions, std::uint32_t material) {
  const float t = (1.0f + std::sqrt(5.0f)) / 2.0f;
  std::vector<glm::vec3> v = {{-1, t, 0},  {1, t, 0},  {-1, -t, 0}, {1, -t, 0}, {0, -1, t},  {0, 1, t},
                              {0, -1, -t}, {0, 1, -t}, {t, 0, -1},  {t, 0, 1},  {-t, 0, -1}, {-t, 0, 1}};
  for (auto& p : v) p = glm::normalize(p);
  std::vector<glm::uvec3> f = {{0, 11, 5},  {0, 5, 1},  {0, 1, 7},  {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                               {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
                               {3, 8, 9},   {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  for (int level = 0; level < subdivisions; ++level) {
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> mid;
    auto midpoint = [&](std::uint32_t a, std::uint32_t b) {
      auto key = std::minmax(a, b);
      auto it = mid.find(key);
      if (it != mid.end()) return it->second;
      v.push_back(glm::normalize(v[a] + v[b]));
      auto idx = static_cast<std::uint32_t>(v.size() - 1);
      mid.emplace(key, idx);
      return idx;
    };
    std::vector<glm::uvec3> next;
    for (const auto& tri : f) {
      std::uint32_t a = midpoint(tri.x, tri.y), b = midpoint(tri.y, tri.z), c = midpoint(tri.z, tri.x);
      next.insert(next.end(), {{tri.x, a, c}, {tri.y, b, a}, {tri.z, c, b}, {a, b, c}});
    }
    f.swap(next);
  }
  auto base = static_cast<std::uint32_t>(s.positions.size());
  bool withNormals = s.normals.size() == s.positions.size();
  for (const auto& p : v) {
    s.positions.push_back(center + radius * p);
    if (withNormals) s.normals.push_back(p);
  }
  for (const auto& tri : f) {
    s.triangles.push_back(tri + glm::uvec3(base));
    s.triangleMaterial.push_back(material);
  }
}

DisplayConfig smallProjectorArray() {
  return parseDisplayConfig(R"({"name": "wall", "model": "projector-array", "spp": 2,
      "projectorArray": {"screen": {"width": 160, "height": 90}, "observerDistance": 300, "observerHeight": 0,
      "angularScattering": "auto", "image": {"width": 24, "height": 12},
      "projectors": [{"position": [-10, 0, -180]}, {"position": [0, 0, -180]}, {"position": [10, 0, -180]},
                     {"position": [20, 0, -180]}]}})",
                            "wall.json", ".");
}

Scene loadBunnyOrEmpty() {
  const char* path = "/usr/share/glmark2/models/bunny.obj";
  if (!std::filesystem::exists(path)) return Scene{};
  return loadScene(path);
}

std::shared_ptr<const RayTable> testRayTable() {
  auto table = std::make_shared<RayTable>();
  table->width = 8;
  table->height = 6;
  for (std::uint32_t y = 0; y < table->height; ++y) {
    for (std::uint32_t x = 0; x < table->width; ++x) {
      const glm::vec3 origin((x + 0.5f) / 8.0f - 0.5f, (y + 0.5f) / 6.0f - 0.5f, 2.0f);
      table->origins.push_back(origin);
      table->directions.push_back(glm::normalize(-origin));
    }
  }
  return table;
}

}  // namespace ht::test
