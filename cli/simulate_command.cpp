// simulate_command.cpp - see simulate_command.h.
#include "cli/simulate_command.h"

#include <array>
#include <cmath>
#include <filesystem>
#include <sstream>
#include <vector>

#include "camera_models/display_config.h"
#include "camera_models/simulated_display_view.h"
#include "cli/arguments.h"
#include "cli/cli_app.h"
#include "cli/image_output.h"
#include "common/error.h"
#include "common/parallel_chunks.h"
#include "frame_io/atomic_output_file.h"
#include "frame_io/frame_reading.h"

namespace ht::cli {
namespace {

const char* const kCommand = "holotrace simulate";
constexpr std::uint32_t kMaxSweep = 64;

const std::array<OptionSpec, 5> kSpecs = {{
    {"--display", "", "SPEC", "the display: config.json, visual.json or builtin:NAME (required)"},
    {"--panel", "", "FILE", "what it shows: the panel / LCD image, or the projector images (multiView EXR, x_v00.png)"},
    {"--output", "-o", "FILE", "the view to write: .png (8-bit sRGB) or .exr (linear half) (required)"},
    {"--eye", "", "X,Y,Z", "eye position in the display's frame (default: the middle of the view cone)"},
    {"--sweep", "", "N", "N eyes across the view cone, left to right, side by side in one image (2-64)"},
}};

glm::dvec3 parseEye(const std::string& text) {
  std::array<double, 3> v{};
  std::istringstream in(text);
  char comma = 0;
  const bool ok = (in >> v[0] >> comma) && comma == ',' && (in >> v[1] >> comma) && comma == ',' && (in >> v[2]) &&
                  (in >> std::ws).eof();
  if (!ok || !std::isfinite(v[0]) || !std::isfinite(v[1]) || !std::isfinite(v[2]) || !(v[2] > 0.0)) {
    throw UsageError(usageMessage(kCommand, "option '--eye' = '" + text +
                                                "': expected X,Y,Z, three finite numbers with Z > 0 (in front of the "
                                                "screen)"));
  }
  return {v[0], v[1], v[2]};
}

std::vector<glm::dvec3> chooseEyes(const ParsedArguments& parsed, const DisplayConfig& display) {
  const auto sweep = parsed.unsignedValue("--sweep", 2, kMaxSweep);
  if (sweep && parsed.has("--eye")) throw UsageError(usageMessage(kCommand, "give '--eye' or '--sweep', not both"));
  if (auto eye = parsed.text("--eye")) return {parseEye(*eye)};
  return displayViewConeEyes(display, sweep.value_or(1));
}

// The views side by side, left to right.
std::vector<float> sideBySide(const std::vector<SimulatedView>& views) {
  const std::uint32_t w = views.front().width, h = views.front().height, n = std::uint32_t(views.size());
  std::vector<float> strip(std::size_t(w) * n * h * 4);
  for (std::uint32_t i = 0; i < n; ++i) {
    for (std::uint32_t row = 0; row < h; ++row) {
      const float* from = &views[i].rgba[std::size_t(row) * w * 4];
      std::copy(from, from + std::size_t(w) * 4, &strip[(std::size_t(row) * w * n + std::size_t(i) * w) * 4]);
    }
  }
  return strip;
}

}  // namespace

std::string simulateHelp() {
  return "Usage: holotrace simulate --display SPEC --panel FILE -o VIEW.png [--eye X,Y,Z | --sweep N]\n\n"
         "Shows what an eye in front of the display sees of a rendered frame, through the display's optics model\n"
         "(the inverse of the per-subpixel mapping `render` traces): for a lenticular panel each pixel shows the\n"
         "subpixel of its colour whose lens sends light to the eye; for a projector array the screen's Gaussian\n"
         "blend of the projectors aimed near the eye; for an integral panel the LCD points each lens shows the eye.\n"
         "The view is the size of the panel (lenticular, integral) or of a projector image across the screen.\n\n"
         "Eye frame: lenticular = origin at the focal-rectangle centre, +z toward the viewer, units of camera.size\n"
         "(\"auto\": the rectangle is 2 units high, the quilt cameras at z = 1/tan(fovyDeg/2)); projector array and\n"
         "integral = display units, screen / lens plane at z = 0. Without --eye: the middle of the view cone.\n"
         "A `render --debug views` phase image seen this way shows the view phase each screen point sends to the\n"
         "eye: one flat grey = one view everywhere; ramps and jumps are crosstalk and view changes "
         "(docs/OPTICS.md).\n\n"
         "Options:\n" +
         formatOptions(kSpecs) +
         "\nExamples:\n"
         "  holotrace render --display builtin:portrait -o out/panel.png\n"
         "  holotrace simulate --display builtin:portrait --panel out/panel.png --eye 0.5,0,8 -o out/view.png\n"
         "  holotrace simulate --display builtin:portrait --panel out/panel.png --sweep 9 -o out/strip.png\n"
         "  holotrace simulate --display builtin:holovizio-wall-70 --panel out/wall_v00.png --sweep 5 -o strip.png\n";
}

int runSimulate(std::span<const std::string> args, std::ostream& out) {
  const ParsedArguments parsed = parseArguments(kCommand, kSpecs, args);
  const std::filesystem::path panelPath = parsed.required("--panel");
  const std::filesystem::path output = parsed.required("--output");
  checkImageOutputPath(kCommand, output);
  const DisplayConfig display = resolveDisplay(parsed.required("--display"));
  const std::vector<glm::dvec3> eyes = chooseEyes(parsed, display);
  const SimulatedViewShape shape = simulatedViewShape(display);
  frame_io::prepareOutputDirectory(output);  // fail before the work, not after it

  const frame_io::ReadFrame frame =
      frame_io::readFrameViews(panelPath, shape.inputWidth, shape.inputHeight, shape.inputViews);
  const DisplayFrameImages images{frame.width, frame.height, frame.views, frame.rgba};
  std::vector<SimulatedView> views;
  for (const glm::dvec3& eye : eyes) {
    views.push_back(simulateDisplayView(display, images, eye, hardwareThreads()));
    out << "eye (" << eye.x << ", " << eye.y << ", " << eye.z << ")\n";
  }
  const std::vector<float> strip = sideBySide(views);
  const auto width = shape.outputWidth * std::uint32_t(views.size());
  writeImageOutput(output, {width, shape.outputHeight, strip});
  out << "display: " << display.name << " (" << displayModelName(display.model) << "), " << views.size()
      << (views.size() == 1 ? " view" : " views side by side") << " of " << shape.outputWidth << "x"
      << shape.outputHeight << "\nwrote " << output.string() << "\n";
  return kExitOk;
}

}  // namespace ht::cli
