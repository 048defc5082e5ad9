// capture_command.cpp - see capture_command.h.
#include "cli/capture_command.h"

#include <algorithm>
#include <array>
#include <filesystem>
#include <vector>

#include "cli/arguments.h"
#include "cli/cluster_render.h"
#include "cli/frame_outputs.h"
#include "cli/render_options.h"
#include "common/error.h"
#include "frame_io/atomic_output_file.h"
#include "frame_io/frame_file_names.h"
#include "frame_io/frame_package.h"

namespace ht::cli {
namespace {

const char* const kCommand = "holotrace capture";
constexpr std::uint32_t kMaxFrames = 1000000;

// The options only capture has; the rest are `holotrace render`'s (without -o, --exr and --debug).
const std::array<OptionSpec, 4> kCaptureSpecs = {{
    {"--frames", "", "N", "frames in the sequence, 1-1000000 (default 1); frame f uses seed + f"},
    {"--name", "", "NAME", "file stem: NAME_f0000.png, NAME_f0001.png, ... (default capture)"},
    {"--format", "", "png|exr", "8-bit sRGB PNG (default) or linear half-float EXR (multiView for many views)"},
    {"--rank-writes", "", "", "under mpirun: each rank writes the frames it renders (the --out-dir is shared)"},
}};

struct CaptureOptions {
  RenderOptions render;
  std::uint32_t frames = 1;
  std::string name = "capture";
  frame_io::FrameFormat format = frame_io::FrameFormat::Png;
  bool rankWrites = false;
};

bool isCaptureOption(const std::string& arg) {
  return std::any_of(kCaptureSpecs.begin(), kCaptureSpecs.end(),
                     [&](const OptionSpec& spec) { return arg == spec.name || arg.starts_with(spec.name + "="); });
}

CaptureOptions parseCaptureOptions(std::span<const std::string> args) {
  std::vector<std::string> own, render;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const bool mine = isCaptureOption(args[i]);
    std::vector<std::string>& to = mine ? own : render;
    to.push_back(args[i]);
    const bool valueFollows = mine && args[i].find('=') == std::string::npos && args[i] != "--rank-writes";
    if (valueFollows && i + 1 < args.size()) to.push_back(args[++i]);
  }
  for (const std::string& arg : render) {
    for (const char* refused : {"-o", "--output", "--exr", "--debug"}) {
      if (arg == refused || arg.starts_with(std::string(refused) + "=")) {
        throw UsageError(
            usageMessage(kCommand, "option '" + std::string(refused) +
                                       "' is not for captures: files are NAME_fNNNN.png/.exr under --out-dir"));
      }
    }
  }
  const ParsedArguments parsed = parseArguments(kCommand, kCaptureSpecs, own);
  CaptureOptions options;
  options.render = parseRenderOptions(render, kCommand);
  options.frames = parsed.unsignedValue("--frames", 1, kMaxFrames).value_or(1);
  options.name = parsed.textOr("--name", options.name);
  if (options.name.empty() || options.name.find('/') != std::string::npos || options.name == "." ||
      options.name == "..") {
    throw UsageError(
        usageMessage(kCommand, "option '--name' = '" + options.name + "': expected a file stem without '/'"));
  }
  const std::string format = parsed.textOr("--format", "png");
  if (format != "png" && format != "exr") {
    throw UsageError(usageMessage(kCommand, "option '--format' = '" + format + "': expected png or exr"));
  }
  options.format = format == "png" ? frame_io::FrameFormat::Png : frame_io::FrameFormat::Exr;
  options.rankWrites = parsed.has("--rank-writes");
  return options;
}

}  // namespace

int runCapture(std::span<const std::string> args, std::ostream& out) {
  const CaptureOptions options = parseCaptureOptions(args);
  FrameSequence sequence;
  sequence.frames = options.frames;
  sequence.ranksWrite = options.rankWrites;
  const std::filesystem::path root = options.render.outDir;
  sequence.prepare = [&](const DisplayConfig& display, const gpu::DisplayCamera& camera) {
    frame_io::prepareOutputDirectory(root / options.name);
    checkViewLayout({display, camera.quilt}, camera.shape.views, options.render.layout);
  };
  sequence.write = [&](std::ostream& log, std::uint32_t frame, const gpu::RenderResult& result,
                       const frame_io::FrameDisplay& display) {
    const std::string fileName = frame_io::captureFrameStem(options.name, frame) +
                                 (options.format == frame_io::FrameFormat::Exr ? ".exr" : ".png");
    frame_io::FramePackage package = frame_io::packageFrame({result.width, result.height, result.views, result.rgba},
                                                            display, options.render.layout, options.format, fileName);
    std::vector<frame_io::OutputFile> files;
    for (frame_io::FrameFile& file : package.files) files.push_back({root / file.name, std::move(file.bytes)});
    frame_io::writeFilesAtomically(files);
    log << "wrote " << (root / files.front().path.filename()).string() << (files.size() > 1 ? " ..." : "") << " ("
        << package.description << ")\n";
  };
  return runFrameSequence(options.render, sequence, out);
}

std::string captureHelp() {
  return "Usage: holotrace capture [options]\n\n"
         "Renders a sequence of frames of one display and scene, frame f with sample seed --seed + f (the daemon's\n"
         "Capture RPC does the same), and writes each whole frame atomically under --out-dir as NAME_f0000.png,\n"
         "NAME_f0001.png, ... (multi-view frames: NAME_fNNNN_qs{cols}x{rows}a{aspect}.png + .json, or\n"
         "NAME_fNNNN_v00.png ...; EXR: one multiView file per frame). Under mpirun (docs/CLUSTER.md) the frames are\n"
         "spread over the ranks and rank 0 writes them, or each rank its own with --rank-writes.\n\n"
         "Options:\n" +
         formatOptions(kCaptureSpecs) +
         "and the render options of `holotrace render --help` except -o, --exr and --debug.\n\n"
         "Examples:\n"
         "  holotrace capture --display builtin:capture-8x6 --scene model.glb --frames 120 --name spin\n"
         "  mpirun -np 4 holotrace capture --display builtin:holovizio-wall-70 --frames 1000 --out-dir /shared/run\n";
}

}  // namespace ht::cli
