// gpu_test_util.h - shared fixtures for the GPU tests.
#pragma once
#include <memory>
#include <vector>

#include <glm/glm.hpp>

#include "camera_models/camera_params.h"
#include "camera_models/display_config.h"
#include "camera_models/ray_table.h"
#include "gpu/renderer.h"
#include "gpu/vulkan_context.h"
#include "scene/scene.h"

namespace ht::test {

// One Vulkan context for the whole test program (device creation costs ~100 ms on lavapipe).
gpu::VulkanContext& sharedContext();

#ifdef HT_SANITIZED_BUILD
constexpr bool kSanitized = true;
#else
constexpr bool kSanitized = false;
#endif

// Pinhole camera at `eye` looking at `target` (+y up), image w x h.
gpu_shared::PinholeParams lookAt(glm::vec3 eye, glm::vec3 target, float fovyDeg, std::uint32_t w, std::uint32_t h);

// Primary rays of every pixel centre of a pinhole camera (the shared C++ pinhole_ray).
std::vector<gpu_shared::HtRay> pinholeRays(const gpu_shared::PinholeParams& p);

// Appends a UV sphere-free icosphere, a quad etc. to a scene with a given material.
std::uint32_t addMaterial(Scene& s, const Material& m);
void addIcosphere(Scene& s, glm::vec3 center, float radius, int subdivisions, std::uint32_t material);
void addQuad(Scene& s, glm::vec3 corner, glm::vec3 edgeU, glm::vec3 edgeV, std::uint32_t material);

// Appends a diffuse (0.7, 0.5, 0.3), a perfect mirror and a glass (ior 1.5) material, in this order.
struct DiffuseMirrorGlass {
  std::uint32_t diffuse, mirror, glass;
};
DiffuseMirrorGlass addDiffuseMirrorGlass(Scene& s);

// An 8 x 6 table of rays converging on the origin from z = 2 (the ray-table model's test camera).
std::shared_ptr<const RayTable> testRayTable();

// A 4-projector array of 24 x 12 images (several small views of pixel targets).
DisplayConfig smallProjectorArray();

// Loads /usr/share/glmark2/models/bunny.obj (the Debian glmark2-data package); empty scene if absent.
Scene loadBunnyOrEmpty();

}  // namespace ht::test
