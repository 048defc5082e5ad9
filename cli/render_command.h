// render_command.h - `holotrace render`: display + scene -> BVH -> GPU frame -> PNG/EXR.
#pragma once
#include <memory>
#include <ostream>
#include <span>
#include <string>

#include "camera_models/display_config.h"
#include "cli/render_options.h"
#include "gpu/renderer.h"
#include "gpu/vulkan_context.h"
#include "scene/scene.h"

namespace ht::cli {

// The render settings of the options (the display's spp unless --spp), with a progress line on a terminal.
gpu::RenderSettings makeRenderSettings(const RenderOptions& options, const DisplayConfig& display);

// Builds the BVH and uploads the scene, then prints the scene and BVH reports.
std::unique_ptr<gpu::Renderer> buildRenderer(std::ostream& out, gpu::VulkanContext& context, const Scene& scene,
                                             double loadMs);

int runRender(std::span<const std::string> args, std::ostream& out);

}  // namespace ht::cli
