// view_mosaic.cpp - see view_mosaic.h.
#include "gpu/view_mosaic.h"

#include <algorithm>
#include <span>

#include <nlohmann/json.hpp>

#include "common/error.h"

namespace ht::gpu {
namespace {

constexpr double kPi = 3.14159265358979323846;

std::span<const float> viewPixels(const RenderResult& frame, std::uint32_t view) {
  const std::size_t floats = std::size_t(frame.width) * frame.height * 4;
  return std::span<const float>(frame.rgba).subspan(view * floats, floats);
}

}  // namespace

std::vector<float> assembleQuilt(const RenderResult& frame, const QuiltLayout& layout) {
  if (frame.views != layout.views() || frame.width != layout.tileWidth || frame.height != layout.tileHeight) {
    throw IoError("quilt layout " + std::to_string(layout.columns) + "x" + std::to_string(layout.rows) + " of " +
                  std::to_string(layout.tileWidth) + "x" + std::to_string(layout.tileHeight) + " tiles does not match " +
                  std::to_string(frame.views) + " views of " + std::to_string(frame.width) + "x" +
                  std::to_string(frame.height) + " (a renderer bug)");
  }
  std::vector<float> quilt(std::size_t(layout.quiltWidth) * layout.quiltHeight * 4, 0.0f);
  for (std::size_t i = 3; i < quilt.size(); i += 4) quilt[i] = 1.0f;
  for (std::uint32_t v = 0; v < frame.views; ++v) {
    const glm::uvec2 origin = quiltTileOrigin(layout, v);  // lower-left, y from the bottom
    const std::span<const float> view = viewPixels(frame, v);
    for (std::uint32_t row = 0; row < frame.height; ++row) {  // row from the top of the view
      const std::uint32_t quiltRowFromBottom = origin.y + (frame.height - 1 - row);
      const std::uint32_t quiltRow = layout.quiltHeight - 1 - quiltRowFromBottom;
      const float* src = view.data() + std::size_t(row) * frame.width * 4;
      float* dst = quilt.data() + (std::size_t(quiltRow) * layout.quiltWidth + origin.x) * 4;
      std::copy(src, src + std::size_t(frame.width) * 4, dst);
    }
  }
  return quilt;
}

RenderResult singleImage(const RenderResult& frame, const std::optional<QuiltLayout>& quilt) {
  if (frame.views == 1) return frame;
  RenderResult image = frame;
  image.views = 1;
  if (quilt) {
    image.rgba = assembleQuilt(frame, *quilt);
    image.width = quilt->quiltWidth;
    image.height = quilt->quiltHeight;
  } else {
    image.height = frame.height * frame.views;  // view-major rows are already view 0 on top
  }
  return image;
}

std::string quiltMetadataJson(const DisplayConfig& display, const DisplayCamera& camera) {
  const QuiltLayout& layout = *camera.quilt;
  nlohmann::json meta;
  meta["generator"] = "holotrace";
  meta["display"] = display.name;
  meta["model"] = std::string(displayModelName(display.model));
  meta["views"] = layout.views();
  meta["columns"] = layout.columns;
  meta["rows"] = layout.rows;
  meta["aspect"] = layout.aspect;
  meta["quiltWidth"] = layout.quiltWidth;
  meta["quiltHeight"] = layout.quiltHeight;
  meta["tileWidth"] = layout.tileWidth;
  meta["tileHeight"] = layout.tileHeight;
  meta["viewOrder"] = "view 0 = bottom-left tile = leftmost (bottom) camera; left to right, then upward";
  if (const auto* quilt = std::get_if<gpu_shared::QuiltParams>(&camera.camera)) {
    meta["viewConeDeg"] = double(quilt->camera.w) * 180.0 / kPi;
    meta["fovyDeg"] = display.camera.fovyDeg;
  }
  if (display.calibration) meta["calibration"] = nlohmann::json::parse(display.calibration->rawJson);
  return meta.dump(2);
}

}  // namespace ht::gpu
