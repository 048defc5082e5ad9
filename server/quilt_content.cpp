// quilt_content.cpp - see quilt_content.h.
#include "server/quilt_content.h"

#include <chrono>

#include "common/error.h"
#include "common/image_limits.h"
#include "common/parallel_chunks.h"
#include "frame_io/quilt_file.h"

namespace ht::server {

namespace {

frame_io::ImageFile decodeQuilt(std::span<const std::uint8_t> bytes, const std::string& fileName) {
  try {
    return frame_io::decodeImage(bytes, fileName);
  } catch (const IoError& e) {
    throw SceneError(fileName, std::string("not a quilt image holotrace can read: ") + e.what() +
                                   " (send a PNG or OpenEXR quilt of at most " + std::to_string(kMaxImageSide) +
                                   " pixels per side)");
  }
}

}  // namespace

QuiltContent::QuiltContent(const std::string& fileName, std::span<const std::uint8_t> bytes)
    : fileName_(fileName), image_(decodeQuilt(bytes, fileName)) {
  frame_io::quiltLayoutOfFile(image_, fileName_);  // refused at load, not at the first frame
}

gpu::RenderResult QuiltContent::frame(const DisplayConfig& display) const {
  const auto start = std::chrono::steady_clock::now();
  const std::string key = display.name + "\n" + display.sourcePath;
  std::shared_ptr<const std::vector<float>> panel;
  {
    std::lock_guard lock(mutex_);
    if (auto it = panels_.find(key); it != panels_.end()) panel = it->second;
  }
  if (!panel) {
    panel = std::make_shared<const std::vector<float>>(
        frame_io::interleaveQuiltImage(image_, fileName_, display, {}, QuiltViewFilter::VendorLerp, hardwareThreads())
            .rgba);
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

}  // namespace ht::server
