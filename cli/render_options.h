// render_options.h - the options of `holotrace render`, parsed and checked before any work starts.
#pragma once
#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <string>

#include "frame_io/view_layout.h"
#include "gpu/display_camera.h"
#include "gpu/renderer.h"

namespace ht::cli {

struct RenderOptions {
  std::string displaySpec = "builtin:portrait";  // config.json, visual.json or builtin:NAME
  std::string sceneSpec = "builtin:showcase";    // .gltf/.glb/.obj or builtin:NAME
  std::optional<std::uint32_t> spp;              // unset: the display config's spp
  std::optional<std::uint32_t> maxDepth;         // unset: RenderSettings default
  std::uint32_t refineSpp = 0;                   // --refine-spp: adaptive refinement off by default
  float refineContrast = gpu::RenderSettings{}.refineContrast;
  std::optional<std::filesystem::path> png;  // -o
  std::optional<std::filesystem::path> exr;  // --exr
  std::filesystem::path outDir = "out";      // where default-named outputs go
  int deviceIndex = -1;                      // -1: automatic choice
  bool validation = false;
  std::uint32_t seed = 0;
  bool noSpecialize = false;
  gpu::CameraPath cameraPath = gpu::CameraPath::Native;  // --quilt: the lenticular display's quilt cameras
  frame_io::ViewLayout layout = frame_io::ViewLayout::Auto;
  gpu::SampleFilter filter = gpu::SampleFilter::Box;
  bool debugViews = false;  // --debug views: no tracing, subpixels coloured by view phase
};

// Throws UsageError ("holotrace render: ...") for unknown options and bad values.
RenderOptions parseRenderOptions(std::span<const std::string> args);

// The help text of `holotrace render`.
std::string renderHelp();

}  // namespace ht::cli
