// bench_stream_main.cpp - holotrace-bench-stream: what progressive accumulation (issue 16, docs/REUSE.md §1-§2)
// buys on a static scene, on a display config scaled down by --scale (lavapipe cannot reference a full Portrait in a
// benchmark's time). Two measurements, both through the code the daemon runs:
//   1. Time to quality (in process, gpu::Renderer): the PSNR of one frame at --spp (vs a --reference-spp frame of
//      another seed) and its time; then progressive frames of --frame-spp samples (uniform, and with the adaptive
//      policy at --target-error) until their PSNR reaches that frame's; ratio = progressive time / single-frame time,
//      per run, median over --runs.
//   2. Work after convergence (an in-process holotraced over gRPC, unix socket): a progressive StreamFrames at
//      120 fps until converged; the process CPU time per wall second while it accumulates (rendering) and in
//      --runs windows of --idle-seconds after convergence; ratio = idle / rendering, and the frames the device
//      rendered meanwhile (must be 0).
// --case selects the scenario: "static" (the two above) or "node-move": per run a fresh accumulation converges (its
// time), then --node moves by 5 % of the scene's diagonal along x and the same accumulation converges again, only
// its targets near the move restarted (docs/REUSE.md §4 in streams); ratio = re-convergence time / first
// convergence time, and the fraction of targets restarted.
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <grpcpp/grpcpp.h>

#include "bench/bench_main.h"
#include "bench/image_metrics.h"
#include "camera_models/display_config.h"
#include "cli/arguments.h"
#include "common/error.h"
#include "gpu/display_camera.h"
#include "gpu/renderer.h"
#include "gpu/vulkan_context.h"
#include "holotrace/v1/holotrace.grpc.pb.h"
#include "scene/scene.h"
#include "scene/scene_edits.h"
#include "server/daemon.h"
#include "server/process_stats.h"

namespace ht::bench {
namespace {

namespace v1 = holotrace::v1;
using Clock = std::chrono::steady_clock;
const char* const kCommand = "holotrace-bench-stream";

struct StreamOptions {
  std::string display = "configs/portrait.json";
  std::string scene = "builtin:showcase";
  std::string benchCase = "static";
  std::string node = "glow-sphere";
  double scale = 0.25;
  std::uint32_t spp = 8, frameSpp = 2, referenceSpp = 64, runs = 5, maxSpp = 64;
  double targetError = 0.02, idleSeconds = 2.0;
  int deviceIndex = -1;
};

const std::array<cli::OptionSpec, 13> kSpecs = {{
    {"--display", "", "FILE", "display config JSON (default configs/portrait.json)"},
    {"--scene", "", "SPEC", "scene (default builtin:showcase)"},
    {"--case", "", "NAME", "scenario: static (default) | node-move (re-convergence after moving --node)"},
    {"--node", "", "NAME", "node-move: the scene node to move (default glow-sphere)"},
    {"--scale", "", "F", "scale of the panel / projector images, DPI kept per panel width (default 0.25)"},
    {"--spp", "", "N", "samples of the single frame whose PSNR progressive frames must reach (default 8)"},
    {"--frame-spp", "", "N", "samples per target of one progressive frame (default 2)"},
    {"--reference-spp", "", "N", "samples of the reference frame (default 64)"},
    {"--target-error", "", "E", "stop rule's error (adaptive policy after --spp samples, daemon stream; default 0.02)"},
    {"--max-spp", "", "N", "stop rule's max samples per target (daemon stream; default 64)"},
    {"--runs", "", "N", "timed runs / idle windows, medians reported (default 5)"},
    {"--idle-seconds", "", "S", "length of one idle window after convergence (default 2)"},
    {"--device", "", "N", "Vulkan device index (default: automatic)"},
}};

std::optional<StreamOptions> parse(std::span<const std::string> args, std::string* help) {
  if (cli::wantsHelp(args)) {
    *help = std::string("Usage: ") + kCommand +
            " [options]\n\nTime to reach a single frame's PSNR progressively, and " +
            "the work per second of a converged progressive stream (docs/BENCHMARKS.md \"Progressive streams\")." +
            "\n\nOptions:\n" + cli::formatOptions(kSpecs);
    return std::nullopt;
  }
  const cli::ParsedArguments parsed = cli::parseArguments(kCommand, kSpecs, args);
  StreamOptions o;
  o.display = parsed.textOr("--display", o.display);
  o.scene = parsed.textOr("--scene", o.scene);
  o.benchCase = parsed.textOr("--case", o.benchCase);
  if (o.benchCase != "static" && o.benchCase != "node-move") {
    throw UsageError(std::string(kCommand) + ": --case " + o.benchCase + ": expected static or node-move");
  }
  o.node = parsed.textOr("--node", o.node);
  o.scale = parsed.numberValue("--scale", 0.01, 1.0).value_or(o.scale);
  o.spp = parsed.unsignedValue("--spp", 1, 1024).value_or(o.spp);
  o.frameSpp = parsed.unsignedValue("--frame-spp", 1, 1024).value_or(o.frameSpp);
  o.referenceSpp = parsed.unsignedValue("--reference-spp", 1, 4096).value_or(o.referenceSpp);
  o.targetError = parsed.numberValue("--target-error", 0.0, 100.0).value_or(o.targetError);
  o.maxSpp = parsed.unsignedValue("--max-spp", 1, 1u << 20).value_or(o.maxSpp);
  o.runs = parsed.unsignedValue("--runs", 1, 100).value_or(o.runs);
  o.idleSeconds = parsed.numberValue("--idle-seconds", 0.1, 600.0).value_or(o.idleSeconds);
  if (auto device = parsed.unsignedValue("--device", 0, 255)) o.deviceIndex = int(*device);
  return o;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : (v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]));
}

double secondsSince(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

double processCpuSeconds() {
  rusage usage{};
  ::getrusage(RUSAGE_SELF, &usage);
  auto seconds = [](const timeval& t) { return double(t.tv_sec) + 1e-6 * double(t.tv_usec); };
  return seconds(usage.ru_utime) + seconds(usage.ru_stime);
}

// The display JSON with its panel (lenticular) or projector images (projector array) scaled; the lenticular DPI scales
// too, so the lens count per panel width -- the optics -- stays the same (as bench/configs/quick-portrait.json).
std::string scaledDisplayJson(const std::string& file, double scale) {
  std::ifstream in(file);
  if (!in) throw Error("cannot read display config " + file);
  nlohmann::json j = nlohmann::json::parse(in);
  auto scaled = [scale](const nlohmann::json& v) { return std::max(1L, std::lround(v.get<double>() * scale)); };
  if (j.contains("calibration") && j["calibration"].is_object()) {
    nlohmann::json& c = j["calibration"];
    c["screenW"] = scaled(c["screenW"]);
    c["screenH"] = scaled(c["screenH"]);
    c["DPI"] = c["DPI"].get<double>() * scale;
  } else if (j.contains("projectorArray")) {
    nlohmann::json& image = j["projectorArray"]["image"];
    image["width"] = scaled(image["width"]);
    image["height"] = scaled(image["height"]);
  } else if (scale != 1.0) {
    throw Error(file + ": --scale applies to lenticular (inline calibration) and projector-array configs only");
  }
  j["name"] = "bench-stream";
  return j.dump(2);
}

struct ProgressiveResult {
  double ms = 0.0;
  std::uint32_t frames = 0, samples = 0;
  double psnr = 0.0;
  double msAtSpp = 0.0, psnrAtSpp = 0.0;  // when every target first had the single frame's spp
};

// Progressive frames until the PSNR reaches `goal` (at most 4x the single frame's samples).
ProgressiveResult accumulateToPsnr(gpu::Renderer& renderer, const gpu::FrameCamera& camera,
                                   const gpu::RenderSettings& frame, const gpu::AccumulationPolicy& policy,
                                   const gpu::RenderResult& reference, double goal, std::uint32_t singleSpp) {
  gpu::Accumulator accumulator(policy);
  ProgressiveResult r;
  double ms = 0.0;
  bool reached = false;
  while (r.samples < 4 * singleSpp && !(reached && r.msAtSpp > 0.0)) {
    const gpu::RenderResult shown = renderer.accumulate(camera, frame, accumulator);
    ms += shown.totalMs;
    const double psnr = compareImages(shown.rgba, reference.rgba, shown.width, shown.height * shown.views).psnrDb;
    if (!reached) {
      r.ms = ms;
      r.frames += 1;
      r.samples = shown.accumulation.maxSamples;
      r.psnr = psnr;
    }
    if (r.msAtSpp == 0.0 && shown.accumulation.minSamples >= singleSpp) {
      r.msAtSpp = ms;
      r.psnrAtSpp = psnr;
    }
    reached = reached || psnr >= goal || shown.accumulation.converged;
  }
  return r;
}

void timeToQuality(const StreamOptions& o, const DisplayConfig& display, const Scene& scene) {
  gpu::VulkanContext context({o.deviceIndex, false});
  gpu::Renderer renderer(context, scene);
  const gpu::DisplayCamera camera = gpu::makeDisplayCamera(display, scene.bounds());
  gpu::RenderSettings single;
  single.spp = o.spp;
  single.seed = 1;
  gpu::RenderSettings reference = single;
  reference.spp = o.referenceSpp;
  reference.seed = 9001;
  gpu::RenderSettings frame = single;
  frame.spp = o.frameSpp;
  gpu::AccumulationPolicy uniform;
  uniform.adaptive = false;
  uniform.maxSpp = 1u << 20;
  gpu::AccumulationPolicy adaptive;
  adaptive.targetError = static_cast<float>(o.targetError);
  adaptive.minSpp = o.spp;  // every target gets the single frame's spp; later samples go where the error is high
  adaptive.maxSpp = 1u << 20;
  std::cout << "frame: " << camera.shape.width << "x" << camera.shape.height << " x " << camera.shape.views
            << " views, " << camera.shape.targets() << " targets\n";
  auto t0 = Clock::now();
  const gpu::RenderResult ref = renderer.render(camera.camera, reference);
  std::cout << "reference spp " << o.referenceSpp << ": " << secondsSince(t0) << " s\n";
  {  // warm-up: every pipeline compiled before the timed runs
    gpu::Accumulator warm(adaptive);
    renderer.render(camera.camera, single);
    renderer.accumulate(camera.camera, frame, warm);
    renderer.accumulate(camera.camera, frame, warm);
  }
  std::vector<double> singleMs, uniformRatio, uniformSppRatio, adaptiveRatio;
  for (std::uint32_t run = 0; run < o.runs; ++run) {
    const gpu::RenderResult one = renderer.render(camera.camera, single);
    const double goal = compareImages(one.rgba, ref.rgba, one.width, one.height * one.views).psnrDb;
    const ProgressiveResult u = accumulateToPsnr(renderer, camera.camera, frame, uniform, ref, goal, o.spp);
    const ProgressiveResult a = accumulateToPsnr(renderer, camera.camera, frame, adaptive, ref, goal, o.spp);
    singleMs.push_back(one.totalMs);
    uniformRatio.push_back(u.ms / one.totalMs);
    uniformSppRatio.push_back(u.msAtSpp / one.totalMs);
    adaptiveRatio.push_back(a.ms / one.totalMs);
    std::printf(
        "run %u: spp %u frame %.0f ms, %.2f dB | uniform: its PSNR after %u frames (%u spp) %.0f ms, %.2f dB; "
        "%u spp after %.0f ms, %.2f dB | adaptive: its PSNR after %u frames (max %u spp) %.0f ms, %.2f dB\n",
        run + 1, o.spp, one.totalMs, goal, u.frames, u.samples, u.ms, u.psnr, o.spp, u.msAtSpp, u.psnrAtSpp, a.frames,
        a.samples, a.ms, a.psnr);
  }
  std::printf(
      "median spp-%u frame %.0f ms; progressive time / single-frame time (medians of same-run ratios): to its "
      "PSNR uniform %.2fx, adaptive %.2fx; to its spp uniform %.2fx\n",
      o.spp, median(singleMs), median(uniformRatio), median(adaptiveRatio), median(uniformSppRatio));
}

// Frames until the stop rule holds everywhere (at most 200); their summed time, count, the first frame's report and
// the last frame's image.
struct Convergence {
  double ms = 0.0;
  std::uint32_t frames = 0;
  gpu::AccumulationReport first;
  double firstMarkMs = 0.0;               // the first frame's marking pass (after a move: which targets restart)
  std::map<std::string, double> stageMs;  // summed over the frames
  std::vector<float> lastRgba;
};

Convergence converge(gpu::Renderer& renderer, const gpu::FrameCamera& camera, const gpu::RenderSettings& frame,
                     gpu::Accumulator& accumulator) {
  Convergence c;
  for (bool done = false; !done && c.frames < 200;) {
    const gpu::RenderResult shown = renderer.accumulate(camera, frame, accumulator);
    if (c.frames == 0) c.first = shown.accumulation;
    for (const gpu::StageTiming& s : shown.stages) {
      c.stageMs[s.name] += s.ms;
      if (c.frames == 0 && s.name == "mark") c.firstMarkMs = s.ms;
    }
    c.ms += shown.totalMs;
    c.frames += 1;
    done = shown.accumulation.converged;
    c.lastRgba = std::move(shown.rgba);
  }
  return c;
}

void nodeMove(const StreamOptions& o, const DisplayConfig& display, Scene scene) {
  const std::optional<std::size_t> node = findNode(scene, o.node);
  if (!node) throw UsageError(std::string(kCommand) + ": --node " + o.node + ": no such node in " + o.scene);
  gpu::VulkanContext context({o.deviceIndex, false});
  gpu::Renderer renderer(context, scene);
  const gpu::DisplayCamera camera = gpu::makeDisplayCamera(display, scene.bounds());
  gpu::RenderSettings frame;
  frame.spp = o.frameSpp;
  frame.seed = 1;
  gpu::AccumulationPolicy policy;
  policy.targetError = static_cast<float>(o.targetError);
  policy.minSpp = o.spp;
  policy.maxSpp = o.maxSpp;
  const Bounds3 sceneBounds = scene.bounds();
  const double step = 0.05 * glm::length(glm::dvec3(sceneBounds.hi - sceneBounds.lo));
  std::cout << "frame: " << camera.shape.targets() << " targets; moving " << o.node << " by " << step
            << " along x and back\n";
  {  // warm-up: the first move switches the scene to the two-level BVH; then the pipelines of recording frames and
     // of a move's marking pass (a move in place) are compiled before the timed runs
    gpu::Accumulator warm(policy);
    renderer.accumulate(camera.camera, frame, warm);
    const std::uint32_t moved[] = {static_cast<std::uint32_t>(*node)};
    renderer.moveNodes(scene, moved);
    gpu::Accumulator recording(policy);
    renderer.accumulate(camera.camera, frame, recording);
    const Bounds3 bounds = nodeWorldBounds(scene, *node);
    renderer.moveNodes(scene, moved, gpu::MovedBounds{bounds, bounds});
    renderer.accumulate(camera.camera, frame, recording);
  }
  std::vector<double> ratio, resetFraction, changedFraction;
  for (std::uint32_t run = 0; run < o.runs; ++run) {
    gpu::Accumulator accumulator(policy);
    const Convergence full = converge(renderer, camera.camera, frame, accumulator);
    const Bounds3 before = nodeWorldBounds(scene, *node);
    const double dx = run % 2 == 0 ? step : -step;
    setNodeWorldMatrix(scene, o.node,
                       glm::translate(glm::dmat4(1.0), glm::dvec3(dx, 0.0, 0.0)) * scene.nodes[*node].world);
    const std::uint32_t moved[] = {static_cast<std::uint32_t>(*node)};
    renderer.moveNodes(scene, moved, gpu::MovedBounds{before, nodeWorldBounds(scene, *node)});
    const Convergence again = converge(renderer, camera.camera, frame, accumulator);
    ratio.push_back(again.ms / full.ms);
    resetFraction.push_back(double(again.first.resetTargets) / double(again.first.targets));
    // What the move changed: the converged frames differ where it did (a restarted target it did not change
    // converges to the same bits, docs/REUSE.md §4 in streams).
    changedFraction.push_back(changedValueFraction(full.lastRgba, again.lastRgba));
    std::printf(
        "run %u: converged in %u frames, %.0f ms; after the move %u frames, %.0f ms (%.3fx), %.2f %% of the "
        "targets restarted%s, %.2f %% of the output values changed\n",
        run + 1, full.frames, full.ms, again.frames, again.ms, again.ms / full.ms, 100.0 * resetFraction.back(),
        again.first.restarted ? " (the whole accumulation restarted)" : "", 100.0 * changedFraction.back());
    std::printf("  after the move, GPU ms summed over its frames:");
    for (const auto& [name, ms] : again.stageMs) std::printf(" %s %.0f", name.c_str(), ms);
    std::printf(" (the marking pass %.1f ms)\n", again.firstMarkMs);
  }
  std::printf(
      "median re-convergence after moving %s: %.3fx the first convergence, %.2f %% of the targets restarted, %.2f %% "
      "of the output values changed\n",
      o.node.c_str(), median(ratio), 100.0 * median(resetFraction), 100.0 * median(changedFraction));
}

// Reads one frame's parts; false at the end of the stream.
bool readHeader(grpc::ClientReaderInterface<v1::FramePart>& reader, v1::FrameHeader& header) {
  v1::FramePart part;
  while (reader.Read(&part)) {
    if (part.has_header()) {
      header = part.header();
      std::uint64_t bytes = 0;
      while (bytes < header.total_bytes() && reader.Read(&part)) bytes += part.chunk().data().size();
      return true;
    }
  }
  return false;
}

std::uint64_t framesRendered(v1::Holotrace::Stub& stub) {
  grpc::ClientContext context;
  v1::StatusResponse status;
  if (!stub.Status(&context, {}, &status).ok() || status.devices_size() == 0) throw Error("Status failed");
  return status.devices(0).frames_rendered();
}

void workAfterConvergence(const StreamOptions& o, const std::string& displayJson) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("holotrace-bench-stream-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir / "displays");
  std::filesystem::create_directories(dir / "scenes");
  std::filesystem::create_directories(dir / "out");
  std::ofstream(dir / "displays" / "bench-stream.json") << displayJson;
  server::DaemonConfig config;
  config.displaysDir = dir / "displays";
  config.sceneRoot = dir / "scenes";
  config.outputRoot = dir / "out";
  config.listen = {"unix:" + (dir / "d.sock").string()};
  config.deviceIndex = o.deviceIndex;
  config.devices.scan = false;
  config.limits.maxAccumulatorBytes = 4ull << 30;
  config.sourcePath = "(holotrace-bench-stream)";
  std::ostringstream log;
  {
    server::Daemon daemon(config, log);
    daemon.start();
    grpc::ChannelArguments args;
    args.SetMaxReceiveMessageSize(64 << 20);
    auto stub =
        v1::Holotrace::NewStub(grpc::CreateCustomChannel(config.listen[0], grpc::InsecureChannelCredentials(), args));
    v1::SceneHandle scene;
    {
      grpc::ClientContext context;
      v1::LoadSceneRequest load;
      load.set_path(o.scene);
      const grpc::Status loaded = stub->LoadScene(&context, load, &scene);
      if (!loaded.ok()) throw Error("LoadScene " + o.scene + ": " + loaded.error_message());
    }
    v1::StreamRequest request;
    request.mutable_render()->set_scene_id(scene.scene_id());
    request.mutable_render()->set_display_id("bench-stream");
    request.mutable_render()->set_spp(o.frameSpp);
    request.set_frames_per_second(120);
    request.set_target_error(static_cast<float>(o.targetError));
    request.set_max_spp(o.maxSpp);
    grpc::ClientContext context;
    auto reader = stub->StreamFrames(&context, request);
    v1::FrameHeader header;
    const auto t0 = Clock::now();
    const double cpu0 = processCpuSeconds();
    std::uint32_t frames = 0;
    while (readHeader(*reader, header)) {
      ++frames;
      if (header.state() == v1::STREAM_STATE_CONVERGED) break;
    }
    if (header.state() != v1::STREAM_STATE_CONVERGED) throw Error("the stream ended before converging");
    const double renderWall = secondsSince(t0), renderCpu = processCpuSeconds() - cpu0;
    std::printf(
        "converged after %u frames, %.1f s: %u-%u spp per target, error estimate %.4f; %.2f CPU s per s "
        "while accumulating\n",
        frames, renderWall, header.accumulated_spp(), header.accumulated_spp_max(), header.error_estimate(),
        renderCpu / renderWall);
    std::vector<double> idleRatio;
    const std::uint64_t renderedBefore = framesRendered(*stub);
    for (std::uint32_t run = 0; run < o.runs; ++run) {
      const auto w0 = Clock::now();
      const double c0 = processCpuSeconds();
      std::this_thread::sleep_for(std::chrono::duration<double>(o.idleSeconds));
      const double perSecond = (processCpuSeconds() - c0) / secondsSince(w0);
      idleRatio.push_back(perSecond / (renderCpu / renderWall));
      std::printf("idle window %u: %.4f CPU s per s (%.3f %% of accumulating)\n", run + 1, perSecond,
                  100.0 * idleRatio.back());
    }
    const std::uint64_t renderedAfter = framesRendered(*stub);
    std::printf("median work after convergence: %.3f %% of rendering; frames rendered meanwhile: %llu\n",
                100.0 * median(idleRatio), static_cast<unsigned long long>(renderedAfter - renderedBefore));
    context.TryCancel();
    while (readHeader(*reader, header)) {}
    reader->Finish();
    daemon.shutdown(std::chrono::milliseconds(0));
  }
  std::filesystem::remove_all(dir);
}

int run(const StreamOptions& o) {
  std::cout << kCommand << " --case " << o.benchCase << " --display " << o.display << " --scene " << o.scene
            << " --scale " << o.scale << " --spp " << o.spp << " --frame-spp " << o.frameSpp << " --reference-spp "
            << o.referenceSpp << " --target-error " << o.targetError << " --max-spp " << o.maxSpp << " --runs "
            << o.runs << "\n";
  const std::string json = scaledDisplayJson(o.display, o.scale);
  const DisplayConfig display = parseDisplayConfig(json, o.display, std::filesystem::path(o.display).parent_path());
  const Scene scene = loadScene(o.scene);
  if (o.benchCase == "node-move") {
    nodeMove(o, display, scene);
    return 0;
  }
  timeToQuality(o, display, scene);
  workAfterConvergence(o, json);
  return 0;
}

}  // namespace
}  // namespace ht::bench

int main(int argc, char** argv) {
  return ht::bench::benchMain(argc, argv, ht::bench::kCommand, ht::bench::parse, ht::bench::run);
}
