// render_options.cpp - see render_options.h.
#include "cli/render_options.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <limits>

#include "cli/arguments.h"
#include "common/error.h"

namespace ht::cli {
namespace {

const char* const kCommand = "holotrace render";
constexpr std::uint32_t kMaxSpp = 4096;  // same bound as the display config's spp
constexpr std::uint32_t kMaxDepth = 32;  // Renderer limit (gpu/renderer.cpp)
constexpr std::uint32_t kMaxDevice = 255;

const std::array<OptionSpec, 11> kSpecs = {{
    {"--display", "", "SPEC", "display: config.json, visual.json or builtin:NAME (default builtin:portrait)"},
    {"--scene", "", "SPEC", "scene: .gltf, .glb, .obj, .off or builtin:NAME (default builtin:showcase)"},
    {"--spp", "", "N", "samples per subpixel (lenticular) or pixel (pinhole), 1-4096 (default: the config's spp)"},
    {"--depth", "", "N", "specular bounces after the primary hit, 0-32 (default 4)"},
    {"--output", "-o", "FILE.png", "write the frame as 8-bit sRGB PNG here"},
    {"--exr", "", "FILE.exr", "write the frame as linear half-float OpenEXR here"},
    {"--out-dir", "", "DIR", "directory for the default outputs <display>_<scene>.png/.exr (default out)"},
    {"--device", "", "N", "Vulkan device index from `holotrace info` (default: automatic)"},
    {"--validation", "", "", "enable the Vulkan validation layer and report its message count"},
    {"--seed", "", "N", "sample-pattern seed (default 0; same seed -> identical frame)"},
    {"--no-specialize", "", "", "run every shading feature even if the scene does not use it"},
}};

bool hasExtension(const std::filesystem::path& path, const std::string& wanted) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return ext == wanted;
}

std::filesystem::path checkedOutputPath(const ParsedArguments& parsed, const std::string& name,
                                        const std::string& extension) {
  const std::filesystem::path path = *parsed.text(name);
  if (!hasExtension(path, extension)) {
    throw UsageError(usageMessage(kCommand, "option '" + name + "' = '" + path.string() + "': expected a path ending in " +
                                                extension));
  }
  return path;
}

}  // namespace

RenderOptions parseRenderOptions(std::span<const std::string> args) {
  const ParsedArguments parsed = parseArguments(kCommand, kSpecs, args);
  RenderOptions options;
  options.displaySpec = parsed.textOr("--display", options.displaySpec);
  options.sceneSpec = parsed.textOr("--scene", options.sceneSpec);
  options.spp = parsed.unsignedValue("--spp", 1, kMaxSpp);
  options.maxDepth = parsed.unsignedValue("--depth", 0, kMaxDepth);
  if (parsed.has("--output")) options.png = checkedOutputPath(parsed, "--output", ".png");
  if (parsed.has("--exr")) options.exr = checkedOutputPath(parsed, "--exr", ".exr");
  options.outDir = parsed.textOr("--out-dir", options.outDir.string());
  if (auto device = parsed.unsignedValue("--device", 0, kMaxDevice)) options.deviceIndex = int(*device);
  options.validation = parsed.has("--validation");
  options.seed = parsed.unsignedValue("--seed", 0, std::numeric_limits<std::uint32_t>::max()).value_or(0);
  options.noSpecialize = parsed.has("--no-specialize");
  return options;
}

std::string renderHelp() {
  return "Usage: holotrace render [options]\n\n"
         "Renders one frame for a light-field display: every panel subpixel gets its own primary rays (lenticular\n"
         "displays) or every pixel a pinhole ray (pinhole displays). Prints device, scene, BVH and per-stage\n"
         "timings. Without -o/--exr it writes <out-dir>/<display>_<scene>.png and .exr.\n\nOptions:\n" +
         formatOptions(kSpecs) +
         "\n"
         "Examples:\n"
         "  holotrace render\n"
         "  holotrace render --display builtin:portrait --scene model.glb --spp 8 -o portrait.png\n"
         "  holotrace render --display visual.json --scene bunny.obj --exr frame.exr\n";
}

}  // namespace ht::cli
