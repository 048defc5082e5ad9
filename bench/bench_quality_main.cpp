// bench_quality_main.cpp - holotrace-bench-quality: run time vs error of the direct lenticular path and the quilt
// path per display (issue 5; method in quality_options.cpp's help text, docs/OPTICS.md §8 "quilt path vs direct").
//
// Every render is timed once per run; --runs N renders every point N times in turn and the comparison uses the
// medians of same-run ratios (single frames on a shared 2-core host are off by 10-15 %, which moves an
// interpolated equal-time gain by +-1 dB, docs/BENCHMARKS.md). Each camera model is warmed up first on a 96x128 copy
// of the display (lavapipe JIT-compiles at the first dispatch).
#include <chrono>
#include <cmath>
#include <ctime>
#include <functional>
#include <iostream>
#include <string>
#include <vector>

#include "bench/bench_main.h"
#include "bench/image_metrics.h"
#include "bench/quality_options.h"
#include "bench/quality_points.h"
#include "camera_models/display_config.h"
#include "camera_models/lenticular_params.h"
#include "camera_models/quilt_interleave.h"
#include "camera_models/quilt_layout.h"
#include "camera_models/quilt_setup.h"
#include "common/error.h"
#include "gpu/display_camera.h"
#include "gpu/renderer.h"
#include "gpu/vulkan_context.h"
#include "scene/scene.h"

namespace ht::bench {
namespace {

using Clock = std::chrono::steady_clock;
constexpr std::uint32_t kRefSeedA = 1001, kRefSeedB = 2002;
constexpr QuiltViewFilter kFilters[] = {QuiltViewFilter::Nearest, QuiltViewFilter::VendorLerp,
                                        QuiltViewFilter::CentredLerp};

struct Context {
  gpu::Renderer& renderer;
  const Scene& scene;
  const QualityOptions& options;
};

// A render of the first run that the later timing runs (--runs) repeat, and the points it times (indices into
// DisplayQuality::points: one, or a quilt's three view filters).
struct Retime {
  explicit Retime(std::function<double()> render) : renderMs(std::move(render)) {}
  std::function<double()> renderMs;
  std::vector<std::size_t> points;
};

gpu::RenderSettings settings(const QualityOptions& o, std::uint32_t spp, std::uint32_t seed) {
  gpu::RenderSettings s;
  s.spp = spp;
  s.maxDepth = o.maxDepth;
  s.seed = seed;
  return s;
}

// Renders one frame and prints its per-pass times (the per-pass breakdown, one line per point).
gpu::RenderResult renderAndPrintStages(const Context& c, const gpu::FrameCamera& camera, const gpu::RenderSettings& s) {
  const gpu::RenderResult frame = c.renderer.render(camera, s);
  std::cout << "   ";
  for (const auto& stage : frame.stages) std::cout << " " << stage.name << " " << std::lround(stage.ms);
  std::cout << " ms" << std::endl;
  return frame;
}

// spp 1 at depth 0 with every target refined at spp 2: compiles the frame's kernels and both refinement passes.
gpu::RenderSettings warmUpSettings(const QualityOptions& o) {
  gpu::RenderSettings s = settings(o, 1, 0);
  s.maxDepth = 0;
  s.refineSpp = 2;
  s.refineContrast = 0.0f;
  return s;
}

double stageSum(const gpu::RenderResult& r) {
  double sum = 0.0;
  for (const auto& stage : r.stages) sum += stage.ms;
  return sum;
}

void scoreAgainst(QualityPoint& p, const std::vector<float>& image, const std::vector<float>& reference,
                  const DisplayQuality& d) {
  p.metrics = compareImages(image, reference, d.panelWidth, d.panelHeight);
  p.psnrCorrectedDb = psnrFromMse(std::max(p.metrics.mse - d.refNoiseMse, 1e-12));
}

// The display's own camera model (and for a lenticular display the quilt cameras) once on a small copy of it.
void warmUp(const Context& c, const DisplayConfig& display, const gpu::FrameCamera& camera) {
  if (!display.calibration) {  // one frame of the real camera: compiles every kernel it uses
    c.renderer.render(camera, warmUpSettings(c.options));
    return;
  }
  DisplayConfig small = display;
  small.calibration->screenW = 96;
  small.calibration->screenH = 128;
  const auto bounds = c.scene.bounds();
  c.renderer.renderLenticular(makeLenticularParams(small, bounds), warmUpSettings(c.options));
  const QuiltLayout layout = defaultQuiltLayout(display);
  const QuiltLayout tiny =
      makeQuiltLayout(layout.columns, layout.rows, layout.columns * 16, layout.rows * 16, layout.aspect);
  c.renderer.renderQuilt(makeQuiltParams(display, bounds, tiny), settings(c.options, 1, 0));
}

// Images are compared as one width x (height * views) image: every view (projector, camera) of the frame.
std::vector<float> renderReference(const Context& c, const gpu::FrameCamera& camera, DisplayQuality& d) {
  const std::uint32_t half = c.options.refSpp / 2;
  std::cout << "  reference: 2 x " << half << " spp..." << std::endl;
  const auto a = c.renderer.render(camera, settings(c.options, half, kRefSeedA));
  const auto b = c.renderer.render(camera, settings(c.options, half, kRefSeedB));
  d.panelWidth = a.width;
  d.panelHeight = a.height * a.views;
  d.refSpp = c.options.refSpp;
  d.refMs = a.totalMs + b.totalMs;
  d.refNoiseMse = compareImages(a.rgba, b.rgba, d.panelWidth, d.panelHeight).mse / 4.0;
  std::vector<float> reference(a.rgba.size());
  for (std::size_t i = 0; i < reference.size(); ++i) reference[i] = 0.5f * (a.rgba[i] + b.rgba[i]);
  return reference;
}

// Appends a measured point with its first run's time, timed again later by `retime`.
void addPoint(DisplayQuality& d, Retime& retime, QualityPoint p) {
  p.runMs = {p.renderMs};
  d.points.push_back(std::move(p));
  retime.points.push_back(d.points.size() - 1);
}

void measureDirect(const Context& c, const gpu::FrameCamera& camera, const std::vector<float>& reference,
                   DisplayQuality& d, std::vector<Retime>& retimes) {
  for (std::uint32_t spp : c.options.directSpp) {
    std::cout << "  direct spp " << spp << "..." << std::endl;
    const gpu::RenderSettings s = settings(c.options, spp, 0);
    const auto frame = renderAndPrintStages(c, camera, s);
    QualityPoint p{"direct", spp, "", "", frame.totalMs, stageSum(frame), 0.0, {}, 0.0};
    scoreAgainst(p, frame.rgba, reference, d);
    addPoint(d, retimes.emplace_back([&c, &camera, s] { return c.renderer.render(camera, s).totalMs; }), p);
  }
}

void measureAdaptive(const Context& c, const gpu::FrameCamera& camera, const std::vector<float>& reference,
                     DisplayQuality& d, std::vector<Retime>& retimes) {
  for (const AdaptivePoint& a : c.options.adaptive) {
    std::cout << "  adaptive spp " << a.baseSpp << " + " << a.refineSpp << " at contrast >= " << a.contrast << "..."
              << std::endl;
    gpu::RenderSettings s = settings(c.options, a.baseSpp, 0);
    s.refineSpp = a.refineSpp;
    s.refineContrast = a.contrast;
    const auto frame = renderAndPrintStages(c, camera, s);
    const double targets = double(gpu::frameShape(camera).targets());
    QualityPoint p{"adaptive", a.baseSpp, "",  "",          frame.totalMs, stageSum(frame),
                   0.0,        {},        0.0, a.refineSpp, a.contrast,    double(frame.refinedTargets) / targets};
    scoreAgainst(p, frame.rgba, reference, d);
    addPoint(d, retimes.emplace_back([&c, &camera, s] { return c.renderer.render(camera, s).totalMs; }), p);
  }
}

void measureQuilt(const Context& c, const DisplayConfig& display, const QuiltLayout& layout,
                  const std::vector<std::uint32_t>& sppList, const std::vector<float>& reference, DisplayQuality& d,
                  std::vector<Retime>& retimes) {
  const auto lenticular = makeLenticularParams(display, c.scene.bounds());
  const auto params = makeQuiltParams(display, c.scene.bounds(), layout);
  const std::string name = std::to_string(layout.columns) + "x" + std::to_string(layout.rows) + " " +
                           std::to_string(layout.tileWidth) + "x" + std::to_string(layout.tileHeight);
  for (std::uint32_t spp : sppList) {
    std::cout << "  quilt " << name << " spp " << spp << "..." << std::endl;
    const gpu::RenderSettings s = settings(c.options, spp, 0);
    const auto frame = c.renderer.renderQuilt(params, s);
    const QuiltViews views = viewStackViews(frame.width, frame.height, frame.views, frame.rgba);
    Retime& retime = retimes.emplace_back([&c, params, s] { return c.renderer.renderQuilt(params, s).totalMs; });
    for (QuiltViewFilter filter : kFilters) {
      const auto start = Clock::now();
      const auto panel = interleaveQuilt(views, lenticular, filter);
      const double interleaveMs = std::chrono::duration<double, std::milli>(Clock::now() - start).count();
      QualityPoint p{"quilt",      spp, name, std::string(quiltViewFilterName(filter)), frame.totalMs, stageSum(frame),
                     interleaveMs, {},  0.0};
      scoreAgainst(p, panel, reference, d);
      addPoint(d, retime, p);
    }
  }
}

// Timing runs 2 .. --runs: every render of the first run again, in the same order, so that each run's ratios share
// one state of the host. Frames are deterministic (same seed, same frame): their scores stay the first run's.
void timeMoreRuns(const Context& c, const std::vector<Retime>& retimes, DisplayQuality& d) {
  d.runs = c.options.runs;
  for (std::uint32_t run = 2; run <= c.options.runs; ++run) {
    std::cout << "  timing run " << run << " of " << c.options.runs << "..." << std::endl;
    for (const Retime& r : retimes) {
      const double ms = r.renderMs();
      for (std::size_t i : r.points) d.points[i].runMs.push_back(ms);
    }
  }
}

QuiltLayout scaledLayout(const QuiltLayout& layout, double scale) {
  const double linear = std::sqrt(scale);
  return makeQuiltLayout(layout.columns, layout.rows, std::uint32_t(std::lround(layout.quiltWidth * linear)),
                         std::uint32_t(std::lround(layout.quiltHeight * linear)), layout.aspect);
}

DisplayQuality measureDisplay(const Context& c, const std::string& spec) {
  const DisplayConfig display = resolveDisplay(spec);
  std::cout << "holotrace-bench-quality: " << spec << std::endl;
  const gpu::FrameCamera camera = gpu::makeDisplayCamera(display, c.scene.bounds(), gpu::CameraPath::Native).camera;
  warmUp(c, display, camera);
  DisplayQuality d;
  d.display = spec;
  const std::vector<float> reference = renderReference(c, camera, d);
  std::vector<Retime> retimes;
  measureDirect(c, camera, reference, d, retimes);
  measureAdaptive(c, camera, reference, d, retimes);
  if (display.calibration) {  // projector arrays, integral panels ...: no quilt path to compare with
    QuiltLayout layout = defaultQuiltLayout(display);
    if (c.options.quiltSize) {
      layout = makeQuiltLayout(layout.columns, layout.rows, c.options.quiltSize->first, c.options.quiltSize->second,
                               layout.aspect);
    }
    measureQuilt(c, display, layout, c.options.quiltSpp, reference, d, retimes);
    measureQuilt(c, display, scaledLayout(layout, c.options.quiltScale), c.options.quiltScaledSpp, reference, d,
                 retimes);
  }
  timeMoreRuns(c, retimes, d);
  return d;
}

std::string utcNow() {
  const std::time_t now = std::time(nullptr);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%d %H:%M UTC", std::gmtime(&now));
  return text;
}

int runBenchmark(const QualityOptions& o) {
  gpu::VulkanContext context({o.deviceIndex, false});
  const Scene scene = loadScene(o.scene);
  gpu::Renderer renderer(context, scene);
  QualityReport report;
  report.device = context.device().name + " (" + context.device().type + ")";
  report.scene = o.scene;
  report.date = utcNow();
  report.maxDepth = o.maxDepth;
  const Context c{renderer, scene, o};
  for (const std::string& display : o.displays) report.displays.push_back(measureDisplay(c, display));
  printQualityReport(std::cout, report);
  if (o.csvPath) writeQualityCsv(*o.csvPath, report);
  if (o.summaryCsvPath) writeQualitySummaryCsv(*o.summaryCsvPath, report);
  if (o.jsonPath) writeQualityJson(*o.jsonPath, report);
  return 0;
}

}  // namespace
}  // namespace ht::bench

int main(int argc, char** argv) {
  return ht::bench::benchMain(
      argc, argv, "holotrace-bench-quality",
      [](const std::vector<std::string>& a, std::string* help) { return ht::bench::parseQualityOptions(a, help); },
      [](const auto& options) { return ht::bench::runBenchmark(options); });
}
