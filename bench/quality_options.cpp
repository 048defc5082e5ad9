// quality_options.cpp - see quality_options.h.
#include "bench/quality_options.h"

#include <array>
#include <cstdio>
#include <cstdlib>
#include <sstream>

#include "cli/arguments.h"
#include "common/error.h"

namespace ht::bench {
namespace {

const char* const kCommand = "holotrace-bench-quality";

const std::array<cli::OptionSpec, 16> kSpecs = {{
    {"--displays", "", "LIST",
     "comma-separated displays of any model (default builtin:portrait,builtin:gen3-16-landscape)"},
    {"--scene", "", "SPEC", "scene (default builtin:plain)"},
    {"--ref-spp", "", "N", "reference spp, even: two independent halves of N/2 (default 16)"},
    {"--spp", "", "LIST", "direct lenticular spp points (default 1,2,4,8)"},
    {"--adaptive", "", "LIST",
     "adaptive points BASE:REFINE:CONTRAST, e.g. 1:8:0.08 (default 1:8:0.12,1:8:0.08,1:8:0.05,1:4:0.08; 'none')"},
    {"--quilt-spp", "", "LIST", "quilt spp points at the device's standard quilt (default 1,2)"},
    {"--quilt-scaled-spp", "", "LIST", "quilt spp points at the scaled quilt (default 1; 'none': no scaled quilt)"},
    {"--quilt-scale", "", "X", "pixel-count factor of the scaled quilt, tiles grow by sqrt(X) (default 2)"},
    {"--quilt-size", "", "WxH",
     "standard quilt texture size (default: the device's, quilt_layout.h); views stay cols x rows"},
    {"--depth", "", "N", "specular bounces, 0-32 (default 4)"},
    {"--runs", "", "N",
     "timing runs, 1-99: every point rendered N times in turn, times = medians of same-run ratios to each quilt "
     "(default 1)"},
    {"--quick", "", "",
     "smoke test: --ref-spp 4 --spp 1,2 --adaptive 1:4:0.08 --quilt-spp 1 --quilt-scaled-spp none (explicit options "
     "win)"},
    {"--device", "", "N", "Vulkan device index (default: automatic)"},
    {"--csv", "", "PATH", "write one row per measured point"},
    {"--summary-csv", "", "PATH", "write the equal-time / equal-error comparison per display"},
    {"--json", "", "PATH", "write every figure as JSON"},
}};

const char* const kHelp =
    "Run time vs error per display, against a reference (direct path at --ref-spp):\n"
    "  direct  the display's own camera model (Renderer::render), every (sub)pixel its own rays, at each --spp;\n"
    "          multi-view frames (projectors, cameras) are scored as one image of all their views\n"
    "  adaptive  the direct path at BASE spp, then REFINE spp on the targets whose sRGB contrast to a neighbour\n"
    "          reaches CONTRAST (RenderSettings::refineSpp, gpu/adaptive_refinement.h)\n"
    "  quilt   lenticular displays only: Renderer::renderQuilt (device default layout, and scaled by --quilt-scale) + "
    "the vendor interleave on\n"
    "          the CPU (camera_models/quilt_interleave.h) with the nearest, vendor-lerp and centred-lerp view filters\n"
    "Per point: ms/frame (render wall time incl. readback; the quilt's CPU interleave is reported apart), RMSE, PSNR, "
    "SSIM on sRGB-encoded [0,1] values, and PSNR\n"
    "corrected for the reference's own noise (MSE - MSE(half A, half B)/4). Summary: at the quilt's time, how many dB\n"
    "the direct path and the adaptive path (the Pareto front of adaptive and direct points) gain (log-time\n"
    "interpolation), and how much faster they reach the quilt's PSNR.\n";

std::vector<std::string> splitText(const std::string& text) {
  std::vector<std::string> items;
  std::stringstream stream(text);
  for (std::string item; std::getline(stream, item, ',');) {
    if (!item.empty()) items.push_back(item);
  }
  return items;
}

std::vector<std::uint32_t> sppList(const cli::ParsedArguments& parsed, const std::string& name,
                                   std::vector<std::uint32_t> fallback) {
  const auto text = parsed.text(name);
  if (!text) return fallback;
  std::vector<std::uint32_t> values;
  if (*text == "none") return values;
  for (const std::string& item : splitText(*text)) {
    char* end = nullptr;
    const unsigned long v = std::strtoul(item.c_str(), &end, 10);
    if (*end != '\0' || v < 1 || v > 4096) {
      throw UsageError(cli::usageMessage(kCommand, name + " entry '" + item + "': expected an integer in [1, 4096]"));
    }
    values.push_back(std::uint32_t(v));
  }
  return values;
}

std::optional<std::pair<std::uint32_t, std::uint32_t>> quiltSizeValue(const cli::ParsedArguments& parsed) {
  const auto text = parsed.text("--quilt-size");
  if (!text) return std::nullopt;
  unsigned w = 0, h = 0;
  char tail = 0;
  if (std::sscanf(text->c_str(), "%ux%u%c", &w, &h, &tail) != 2 || w < 1 || h < 1 || w > 16384 || h > 16384) {
    throw UsageError(cli::usageMessage(kCommand, "--quilt-size '" + *text + "': expected WxH, e.g. 3360x3360"));
  }
  return std::pair{std::uint32_t(w), std::uint32_t(h)};
}

std::vector<AdaptivePoint> adaptiveList(const cli::ParsedArguments& parsed, std::vector<AdaptivePoint> fallback) {
  const auto text = parsed.text("--adaptive");
  if (!text) return fallback;
  std::vector<AdaptivePoint> points;
  if (*text == "none") return points;
  for (const std::string& item : splitText(*text)) {
    unsigned base = 0, refine = 0;
    float contrast = 0.0f;
    char tail = 0;
    if (std::sscanf(item.c_str(), "%u:%u:%f%c", &base, &refine, &contrast, &tail) != 3 || base < 1 || base > 4096 ||
        refine < 1 || refine > 4096 || !(contrast >= 0.0f && contrast <= 1.0f)) {
      throw UsageError(cli::usageMessage(kCommand, "--adaptive entry '" + item +
                                                       "': expected BASE:REFINE:CONTRAST with "
                                                       "spp in [1, 4096] and a contrast in [0, 1], e.g. 1:8:0.08"));
    }
    points.push_back({base, refine, contrast});
  }
  return points;
}

}  // namespace

std::optional<QualityOptions> parseQualityOptions(std::span<const std::string> args, std::string* helpText) {
  if (cli::wantsHelp(args)) {
    *helpText =
        std::string("Usage: ") + kCommand + " [options]\n\n" + kHelp + "\nOptions:\n" + cli::formatOptions(kSpecs);
    return std::nullopt;
  }
  const cli::ParsedArguments parsed = cli::parseArguments(kCommand, kSpecs, args);
  QualityOptions o;
  const bool quick = parsed.has("--quick");
  if (auto displays = parsed.text("--displays")) o.displays = splitText(*displays);
  if (o.displays.empty()) throw UsageError(cli::usageMessage(kCommand, "--displays is empty"));
  o.scene = parsed.textOr("--scene", o.scene);
  o.refSpp = parsed.unsignedValue("--ref-spp", 2, 4096).value_or(quick ? 4 : o.refSpp);
  if (o.refSpp % 2) throw UsageError(cli::usageMessage(kCommand, "--ref-spp must be even (two halves)"));
  o.directSpp = sppList(parsed, "--spp", quick ? std::vector<std::uint32_t>{1, 2} : o.directSpp);
  o.adaptive = adaptiveList(parsed, quick ? std::vector<AdaptivePoint>{{1, 4, 0.08f}} : o.adaptive);
  o.quiltSpp = sppList(parsed, "--quilt-spp", quick ? std::vector<std::uint32_t>{1} : o.quiltSpp);
  o.quiltScaledSpp = sppList(parsed, "--quilt-scaled-spp", quick ? std::vector<std::uint32_t>{} : o.quiltScaledSpp);
  o.quiltScale = parsed.numberValue("--quilt-scale", 0.25, 16.0).value_or(o.quiltScale);
  o.quiltSize = quiltSizeValue(parsed);
  o.maxDepth = parsed.unsignedValue("--depth", 0, 32).value_or(o.maxDepth);
  o.runs = parsed.unsignedValue("--runs", 1, 99).value_or(o.runs);
  if (o.directSpp.empty()) throw UsageError(cli::usageMessage(kCommand, "--spp is empty"));
  if (auto device = parsed.unsignedValue("--device", 0, 255)) o.deviceIndex = int(*device);
  o.csvPath = parsed.text("--csv");
  o.summaryCsvPath = parsed.text("--summary-csv");
  o.jsonPath = parsed.text("--json");
  return o;
}

}  // namespace ht::bench
