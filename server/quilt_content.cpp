// quilt_content.cpp - see quilt_content.h.
#include "server/quilt_content.h"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <filesystem>

#include "camera_models/lenticular_params.h"
#include "common/error.h"
#include "common/parallel_chunks.h"
#include "frame_io/quilt_file.h"

namespace ht::server {

QuiltContent::QuiltContent(const std::string& fileName, std::span<const std::uint8_t> bytes)
    : fileName_(fileName), image_(frame_io::decodeImage(bytes, fileName)) {}

gpu::RenderResult QuiltContent::frame(const DisplayConfig& display) const {
  const auto start = std::chrono::steady_clock::now();
  const std::string key = display.name + "\n" + display.sourcePath;
  std::shared_ptr<const std::vector<float>> panel;
  {
    std::lock_guard lock(mutex_);
    if (auto it = panels_.find(key); it != panels_.end()) panel = it->second;
  }
  if (!panel) {
    const frame_io::QuiltFileLayout layout = frame_io::resolveQuiltLayout(image_, fileName_, {}, display);
    checkQuiltFitsDisplay(layout.layout, display, fileName_);
    const gpu_shared::LenticularParams params = makeLenticularParams(display, Bounds3{});
    panel = std::make_shared<const std::vector<float>>(interleaveQuilt(
        quiltImageViews(layout.layout, image_.rgba), params, QuiltViewFilter::VendorLerp, hardwareThreads()));
    std::lock_guard lock(mutex_);
    panels_.emplace(key, panel);
  }
  gpu::RenderResult result;
  result.width = display.calibration->screenW;
  result.height = display.calibration->screenH;
  result.rgba = *panel;
  result.totalMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  result.stages.push_back({"interleave", result.totalMs});
  return result;
}

bool isQuiltSpec(const std::string& spec) {
  std::string ext = std::filesystem::path(spec).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return ext == ".png" || ext == ".exr";
}

}  // namespace ht::server
