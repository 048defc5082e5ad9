// render_report.h - the human-readable lines `holotrace render` prints: device, scene, BVH, frame.
#pragma once
#include <ostream>
#include <string>

#include "bvh/bvh_builder.h"
#include "gpu/renderer.h"
#include "gpu/vulkan_context.h"
#include "scene/scene.h"

namespace ht::cli {

void printDevice(std::ostream& out, const gpu::DeviceInfo& device);
void printScene(std::ostream& out, const Scene& scene, const SceneFeatures& features);
void printBvh(std::ostream& out, const bvh::BuildReport& report);
// Per-stage GPU timings, rays traced and Mrays/s over the frame's wall time.
void printFrame(std::ostream& out, const gpu::RenderResult& result);

// "12.3 ms" (one decimal).
std::string formatMs(double ms);

// "lights, mirrors, textures" or "none".
std::string featureList(const SceneFeatures& features);

}  // namespace ht::cli
