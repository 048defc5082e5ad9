// frame_outputs.cpp - see frame_outputs.h.
#include "cli/frame_outputs.h"

#include <cmath>
#include <fstream>
#include <span>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli/atomic_output_file.h"
#include "cli/image_file_writer.h"
#include "common/error.h"

namespace ht::cli {
namespace fs = std::filesystem;
namespace {

std::span<const float> viewPixels(const gpu::RenderResult& frame, std::uint32_t view) {
  const std::size_t floats = std::size_t(frame.width) * frame.height * 4;
  return std::span<const float>(frame.rgba).subspan(view * floats, floats);
}

std::string viewName(std::uint32_t view, std::uint32_t views, const char* prefix) {
  const std::size_t digits = std::max<std::size_t>(2, std::to_string(views - 1).size());
  std::string number = std::to_string(view);
  return prefix + std::string(digits - number.size(), '0') + number;
}

const char* viewPrefix(const gpu::DisplayCamera& camera) {
  return std::holds_alternative<gpu_shared::ProjectorArrayParams>(camera.camera) ? "projector" : "view";
}

fs::path withSuffix(const fs::path& path, const std::string& suffix) {
  fs::path result = path;
  result.replace_filename(path.stem().string() + suffix + path.extension().string());
  return result;
}

void writeTextFile(const fs::path& path, const std::string& text) {
  AtomicOutputFile file(path);
  {
    std::ofstream stream(file.tempPath(), std::ios::binary);
    stream << text;
    stream.flush();
    if (!stream) throw IoError("cannot write '" + path.string() + "': write failed (disk full?)");
  }
  file.commit();
}

void writeSingle(std::ostream& out, const OutputPaths& paths, const gpu::RenderResult& frame) {
  const RgbaImageView image{frame.width, frame.height, frame.rgba};
  if (paths.png) {
    writeImageFile(*paths.png, image, ImageFormat::Png8Srgb);
    out << "wrote " << paths.png->string() << " (" << frame.width << "x" << frame.height << ", 8-bit sRGB PNG)\n";
  }
  if (paths.exr) {
    writeImageFile(*paths.exr, image, ImageFormat::ExrHalf);
    out << "wrote " << paths.exr->string() << " (" << frame.width << "x" << frame.height << ", linear half EXR)\n";
  }
}

void writeQuilt(std::ostream& out, const fs::path& requested, const gpu::RenderResult& frame,
                const DisplayConfig& display, const gpu::DisplayCamera& camera) {
  const QuiltLayout& layout = *camera.quilt;
  const fs::path path = quiltFilePath(requested, layout);
  const std::vector<float> quilt = gpu::assembleQuilt(frame, layout);
  const std::string metadata = gpu::quiltMetadataJson(display, camera);
  writeImageFile(path, {layout.quiltWidth, layout.quiltHeight, quilt}, ImageFormat::Png8Srgb,
                 {{"ImageDescription", metadata}});
  fs::path sidecar = path;
  sidecar.replace_extension(".json");
  writeTextFile(sidecar, metadata + "\n");
  out << "wrote " << path.string() << " (quilt " << layout.columns << "x" << layout.rows << " of "
      << layout.tileWidth << "x" << layout.tileHeight << " tiles, " << layout.quiltWidth << "x" << layout.quiltHeight
      << ", 8-bit sRGB PNG) + " << sidecar.filename().string() << "\n";
}

void writeViewSequence(std::ostream& out, const fs::path& requested, const gpu::RenderResult& frame,
                       const gpu::DisplayCamera& camera) {
  for (std::uint32_t v = 0; v < frame.views; ++v) {
    const fs::path path = withSuffix(requested, "_" + viewName(v, frame.views, "v"));
    writeImageFile(path, {frame.width, frame.height, viewPixels(frame, v)}, ImageFormat::Png8Srgb);
  }
  out << "wrote " << frame.views << " " << viewPrefix(camera) << " images "
      << withSuffix(requested, "_" + viewName(0, frame.views, "v")).string() << " ... "
      << withSuffix(requested, "_" + viewName(frame.views - 1, frame.views, "v")).filename().string() << " ("
      << frame.width << "x" << frame.height << ", 8-bit sRGB PNG)\n";
}

void writeMultiView(std::ostream& out, const fs::path& path, const gpu::RenderResult& frame,
                    const gpu::DisplayCamera& camera) {
  std::vector<std::string> names;
  for (std::uint32_t v = 0; v < frame.views; ++v) names.push_back(viewName(v, frame.views, viewPrefix(camera)));
  writeMultiViewExr(path, frame.width, frame.height, frame.rgba, names, ImageFormat::ExrHalf);
  out << "wrote " << path.string() << " (" << frame.views << " views of " << frame.width << "x" << frame.height
      << ", linear half EXR, multiView)\n";
}

}  // namespace

fs::path quiltFilePath(const fs::path& path, const QuiltLayout& layout) {
  if (path.filename().string().find("_qs") != std::string::npos) return path;
  return withSuffix(path, formatQuiltName(layout.columns, layout.rows, layout.aspect));
}

void writeFrameOutputs(std::ostream& out, const OutputPaths& paths, const gpu::RenderResult& frame,
                       const DisplayConfig& display, const gpu::DisplayCamera& camera, ViewLayout layout) {
  if (frame.views == 1) {
    writeSingle(out, paths, frame);
    return;
  }
  if (layout == ViewLayout::Quilt && !camera.quilt) {
    throw UsageError("holotrace render: --layout quilt: the " + std::to_string(frame.views) + " views of a '" +
                     std::string(displayModelName(display.model)) + "' display do not form a quilt; use --layout views");
  }
  const bool quilt = camera.quilt && layout != ViewLayout::Views;
  if (paths.png) {
    if (quilt) writeQuilt(out, *paths.png, frame, display, camera);
    else writeViewSequence(out, *paths.png, frame, camera);
  }
  if (paths.exr) writeMultiView(out, *paths.exr, frame, camera);
}

}  // namespace ht::cli
