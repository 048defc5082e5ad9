// primary_ray_batch.h - the benchmark's primary rays: one pinhole ray per pixel through the pixel centre,
// camera on the +z side of the mesh looking at its bounds centre, framed so the mesh fills the image.
// Both tracers get exactly these rays.
#pragma once
#include <cstdint>
#include <vector>

#include "bvh/ray_types.h"
#include "scene/scene.h"

namespace ht::bench {

struct RayBatch {
  std::uint32_t width = 0, height = 0;
  std::vector<gpu_shared::HtRay> rays;  // row-major, row 0 = bottom (docs/OPTICS.md §0), unit directions
};

RayBatch makePinholeRays(const Bounds3& bounds, std::uint32_t size);

}  // namespace ht::bench
