// quilt_content.h - a quilt image loaded as scene-like content (docs/SERVICE.md §12): LoadScene of a `.png` / `.exr`
// quilt (a `_qs{c}x{r}a{aspect}` name or holotrace's embedded metadata) gives a session whose frames are the quilt
// interleaved for the requested lenticular display with the vendor's view filter (frame_io/quilt_file.h), so
// RenderFrame, StreamFrames, Capture and display sinks show existing quilt content unchanged. Nothing is traced; the
// interleaved panel is computed once per display and kept with the content.
#pragma once
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <span>
#include <string>
#include <vector>

#include "camera_models/display_config.h"
#include "frame_io/image_reading.h"
#include "gpu/renderer.h"

namespace ht::server {

class QuiltContent {
 public:
  // Decodes the quilt and checks what needs no display (frame_io::quiltLayoutOfFile): a layout from the name's
  // `_qs` tag or the embedded metadata, both agreeing, 2 to 4096 views, tiles of at least 2x2 pixels. Throws
  // SceneError for bytes that are no readable PNG / EXR or exceed the image limits (common/image_limits.h), ConfigError
  // naming the file and field for the layout.
  QuiltContent(const std::string& fileName, std::span<const std::uint8_t> bytes);

  // The quilt interleaved for `display`: one view of screenW x screenH. Throws ConfigError (naming the quilt file)
  // when its layout is unknown or it cannot fit the display (not lenticular, aspect, tile count or size).
  gpu::RenderResult frame(const DisplayConfig& display) const;

  const std::string& fileName() const { return fileName_; }
  std::uint32_t width() const { return image_.width; }
  std::uint32_t height() const { return image_.height; }
  // Host memory of the decoded quilt (linear float RGBA), for the daemon's scene memory budget.
  std::uint64_t memoryBytes() const { return image_.rgba.size() * sizeof(float); }

 private:
  std::string fileName_;
  frame_io::ImageFile image_;
  mutable std::mutex mutex_;
  mutable std::map<std::string, std::shared_ptr<const std::vector<float>>> panels_;  // by display name + source
};

}  // namespace ht::server
