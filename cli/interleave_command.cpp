// interleave_command.cpp - see interleave_command.h.
#include "cli/interleave_command.h"

#include <array>
#include <chrono>
#include <filesystem>

#include "camera_models/display_config.h"
#include "cli/arguments.h"
#include "cli/cli_app.h"
#include "cli/image_output.h"
#include "common/error.h"
#include "common/parallel_chunks.h"
#include "frame_io/atomic_output_file.h"
#include "frame_io/quilt_file.h"

namespace ht::cli {
namespace {

const char* const kCommand = "holotrace interleave";
constexpr std::uint32_t kMaxCount = 1024;  // columns, rows: as the quilt name (camera_models/quilt_layout.h)

const std::array<OptionSpec, 7> kSpecs = {{
    {"--display", "", "SPEC", "the lenticular display: config.json, visual.json or builtin:NAME (required)"},
    {"--quilt", "", "FILE", "the quilt image (.png or .exr), e.g. take_qs8x6a0.75.png (required)"},
    {"--output", "-o", "FILE", "the panel image to write: .png (8-bit sRGB) or .exr (linear half) (required)"},
    {"--filter", "", "NAME", "view filter: vendor (default, the vendor's lerp), centred (better) or nearest"},
    {"--columns", "", "N", "tile columns, with --rows: overrides the file name's tag and the metadata"},
    {"--rows", "", "N", "tile rows, with --columns"},
    {"--aspect", "", "X", "render aspect W/H of the quilt's cameras (default: the tag, metadata or the display's)"},
}};

double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

std::string interleaveHelp() {
  return "Usage: holotrace interleave --display SPEC --quilt FILE -o PANEL.png [options]\n\n"
         "Interleaves a quilt image (Looking Glass tools or `holotrace render --quilt`) into the native panel image\n"
         "of a lenticular display: every subpixel takes the view its lens phase addresses, sampled at the pixel's\n"
         "position in the view. The tile layout comes from --columns/--rows/--aspect, else the file name's\n"
         "_qs{columns}x{rows}a{aspect} tag, else the metadata holotrace embeds in its quilts. A quilt whose render\n"
         "aspect, tile count or tile size cannot fit the display is refused, naming the value.\n\n"
         "View filters: vendor = mix of views floor(tN) and floor(tN)+1 by fract(tN), as the vendor's shaders do;\n"
         "centred = the same between the two views whose cameras bracket the phase (half a view closer to the\n"
         "direct render, see docs/BENCHMARKS.md); nearest = one view per subpixel.\n\nOptions:\n" +
         formatOptions(kSpecs) +
         "\nExamples:\n"
         "  holotrace render --display builtin:portrait --quilt -o out/take.png   (-> out/take_qs8x6a0.75.png)\n"
         "  holotrace interleave --display builtin:portrait --quilt out/take_qs8x6a0.75.png -o out/panel.png\n"
         "  holotrace interleave --display visual.json --quilt hologram.png --columns 8 --rows 6 --aspect 0.75 \\\n"
         "      --filter centred -o panel.png\n";
}

int runInterleave(std::span<const std::string> args, std::ostream& out) {
  const auto start = std::chrono::steady_clock::now();
  const ParsedArguments parsed = parseArguments(kCommand, kSpecs, args);
  const std::filesystem::path quiltPath = parsed.required("--quilt");
  const std::filesystem::path output = parsed.required("--output");
  checkImageOutputPath(kCommand, output);
  const QuiltViewFilter filter = parseQuiltViewFilter(parsed.textOr("--filter", "vendor"));
  frame_io::QuiltLayoutHints hints;
  hints.columns = parsed.unsignedValue("--columns", 1, kMaxCount);
  hints.rows = parsed.unsignedValue("--rows", 1, kMaxCount);
  hints.aspect = parsed.numberValue("--aspect", 1e-3, 1e3);
  if (hints.columns.has_value() != hints.rows.has_value()) {
    throw UsageError(usageMessage(kCommand, "give both '--columns' and '--rows', or neither"));
  }
  const DisplayConfig display = resolveDisplay(parsed.required("--display"));
  frame_io::prepareOutputDirectory(output);  // fail before the work, not after it

  const frame_io::InterleavedQuilt panel =
      frame_io::interleaveQuiltFile(quiltPath, display, hints, filter, hardwareThreads());
  const QuiltLayout& layout = panel.layout.layout;
  out << "quilt: " << quiltPath.string() << ", " << layout.columns << "x" << layout.rows << " views of "
      << layout.tileWidth << "x" << layout.tileHeight << " (layout from the " << panel.layout.source
      << ", render aspect " << layout.aspect << ")\n"
      << "display: " << display.name << " " << panel.width << "x" << panel.height << ", filter "
      << quiltViewFilterName(filter) << "\n";
  writeImageOutput(output, {panel.width, panel.height, panel.rgba});
  out << "wrote " << output.string() << " in " << secondsSince(start) << " s\n";
  return kExitOk;
}

}  // namespace ht::cli
