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

const std::array<OptionSpec, 17> kSpecs = {{
    {"--display", "", "SPEC", "display: config.json, visual.json or builtin:NAME (default builtin:portrait)"},
    {"--scene", "", "SPEC", "scene: .gltf, .glb, .obj, .off or builtin:NAME (default builtin:showcase)"},
    {"--spp", "", "N",
     "samples per subpixel (lenticular, integral) or pixel (other models), 1-4096 (default: the config's spp)"},
    {"--refine-spp", "", "N",
     "adaptive refinement: trace targets of high contrast again at N spp, 0-4096 (default 0 = off)"},
    {"--refine-contrast", "", "X", "sRGB step to a neighbour that marks a target for refinement, 0-1 (default 0.08)"},
    {"--filter", "", "NAME", "reconstruction filter over each footprint: box, tent or gaussian (default box)"},
    {"--quilt", "", "", "lenticular displays: render the vendor quilt views instead of per-subpixel rays"},
    {"--layout", "", "NAME",
     "multi-view frames in -o: auto, quilt or views (default auto: quilt if the views form one)"},
    {"--debug", "", "views", "no tracing: colour each subpixel by its view phase (lenticular displays)"},
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
    throw UsageError(usageMessage(
        kCommand, "option '" + name + "' = '" + path.string() + "': expected a path ending in " + extension));
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
  options.refineSpp = parsed.unsignedValue("--refine-spp", 0, kMaxSpp).value_or(0);
  options.refineContrast =
      static_cast<float>(parsed.numberValue("--refine-contrast", 0.0, 1.0).value_or(options.refineContrast));
  if (parsed.has("--refine-contrast") && options.refineSpp == 0) {
    throw UsageError(
        usageMessage(kCommand, "option '--refine-contrast' needs '--refine-spp N' (N > 0) to take effect"));
  }
  if (parsed.has("--output")) options.png = checkedOutputPath(parsed, "--output", ".png");
  if (parsed.has("--exr")) options.exr = checkedOutputPath(parsed, "--exr", ".exr");
  options.outDir = parsed.textOr("--out-dir", options.outDir.string());
  if (auto device = parsed.unsignedValue("--device", 0, kMaxDevice)) options.deviceIndex = int(*device);
  options.validation = parsed.has("--validation");
  options.seed = parsed.unsignedValue("--seed", 0, std::numeric_limits<std::uint32_t>::max()).value_or(0);
  options.noSpecialize = parsed.has("--no-specialize");
  if (parsed.has("--quilt")) options.cameraPath = gpu::CameraPath::Quilt;
  if (auto text = parsed.text("--layout")) {
    auto layout = frame_io::parseViewLayout(*text);
    if (!layout)
      throw UsageError(usageMessage(kCommand, "option '--layout' = '" + *text + "': expected auto, quilt or views"));
    options.layout = *layout;
  }
  if (auto text = parsed.text("--filter")) {
    if (*text == "box")
      options.filter = gpu::SampleFilter::Box;
    else if (*text == "tent")
      options.filter = gpu::SampleFilter::Tent;
    else if (*text == "gaussian")
      options.filter = gpu::SampleFilter::Gaussian;
    else
      throw UsageError(usageMessage(kCommand, "option '--filter' = '" + *text + "': expected box, tent or gaussian"));
  }
  if (auto text = parsed.text("--debug")) {
    if (*text != "views")
      throw UsageError(usageMessage(kCommand, "option '--debug' = '" + *text + "': expected views"));
    options.debugViews = true;
  }
  return options;
}

std::string renderHelp() {
  return "Usage: holotrace render [options]\n\n"
         "Renders one frame for a light-field display through its own optics: every panel subpixel gets its own\n"
         "primary rays (lenticular, integral), every projector pixel its double-perspective ray (projector arrays),\n"
         "every view pixel its ray (capture grids, pinhole). Prints device, scene, BVH and per-stage timings.\n"
         "Without -o/--exr it writes <out-dir>/<display>_<scene>.png and .exr. Multi-view frames go to a quilt\n"
         "(<stem>_qs{cols}x{rows}a{aspect}.png + .json metadata) or one PNG per view (<stem>_v00.png, ...), and\n"
         "to one EXR with the multiView attribute.\n\nOptions:\n" +
         formatOptions(kSpecs) +
         "\n"
         "Examples:\n"
         "  holotrace render\n"
         "  holotrace render --display builtin:portrait --scene model.glb --spp 8 -o portrait.png\n"
         "  holotrace render --display visual.json --scene bunny.obj --exr frame.exr\n"
         "  holotrace render --display builtin:portrait --quilt -o out/portrait.png   (-> portrait_qs8x6a0.75.png)\n"
         "  holotrace render --display builtin:holovizio-wall-70 --spp 2 -o out/wall.png   (-> wall_v00.png ...)\n"
         "  holotrace render --display builtin:portrait --debug views -o phase.png\n"
         "  holotrace render --spp 1 --refine-spp 8 --refine-contrast 0.08   (8 spp where the 1-spp frame has edges)\n";
}

}  // namespace ht::cli
