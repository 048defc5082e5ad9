// frame_outputs.cpp - see frame_outputs.h.
#include "cli/frame_outputs.h"

#include <string>
#include <vector>

#include "common/error.h"
#include "frame_io/atomic_output_file.h"

namespace ht::cli {
namespace fs = std::filesystem;
namespace {

// "dir/a.png" for one file, "dir/a_qs3x2a1.5.png + a_qs3x2a1.5.json" for two, "dir/a_v00.png ... a_v05.png" beyond.
std::string fileList(const fs::path& directory, const std::vector<frame_io::FrameFile>& files) {
  std::string list = (directory / files.front().name).string();
  if (files.size() == 2) list += " + " + files.back().name;
  if (files.size() > 2) list += " ... " + files.back().name;
  return list;
}

}  // namespace

void checkViewLayout(const frame_io::FrameDisplay& display, std::uint32_t views, frame_io::ViewLayout layout) {
  if (frame_io::layoutAllowed(display, views, layout)) return;
  throw UsageError("holotrace render: --layout quilt: the " + std::to_string(views) + " views of a '" +
                   std::string(displayModelName(display.config.model)) +
                   "' display do not form a quilt; use --layout views");
}

void writeFrameOutputs(std::ostream& out, const OutputPaths& paths, const gpu::RenderResult& frame,
                       const frame_io::FrameDisplay& display, frame_io::ViewLayout layout) {
  checkViewLayout(display, frame.views, layout);
  const frame_io::FrameImages images{frame.width, frame.height, frame.views, frame.rgba};
  std::vector<std::string> lines;
  std::vector<frame_io::OutputFile> files;
  const auto add = [&](const fs::path& requested, frame_io::FrameFormat format) {
    frame_io::FramePackage package =
        frame_io::packageFrame(images, display, layout, format, requested.filename().string());
    lines.push_back("wrote " + fileList(requested.parent_path(), package.files) + " (" + package.description + ")");
    for (frame_io::FrameFile& file : package.files) {
      files.push_back({requested.parent_path() / file.name, std::move(file.bytes)});
    }
  };
  if (paths.png) add(*paths.png, frame_io::FrameFormat::Png);
  if (paths.exr) add(*paths.exr, frame_io::FrameFormat::Exr);
  frame_io::writeFilesAtomically(files);
  for (const std::string& line : lines) out << line << "\n";
}

}  // namespace ht::cli
