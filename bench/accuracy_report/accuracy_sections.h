// accuracy_sections.h - the measured sections of docs/ACCURACY.md, each returning Markdown.
#pragma once
#include <cstdint>
#include <string>

namespace ht::gpu {
class VulkanContext;
}

namespace ht::accuracy::report {

// Rays from inside every closed mesh at every placement, split evenly over placements and ray kinds:
// holotrace CPU and GPU, robust Embree, naive Möller-Trumbore controls. `raysPerMesh` over all placements.
std::string watertightSection(gpu::VulkanContext& context, uint64_t raysPerMesh);

// Embree differential on random interior rays (closed meshes at the origin and Embree verify's centre) and
// exterior rays on the bunny: agreement, t agreement, classified disagreements, the first ones listed.
std::string differentialSection(gpu::VulkanContext& context, uint64_t raysPerCase);

}  // namespace ht::accuracy::report
