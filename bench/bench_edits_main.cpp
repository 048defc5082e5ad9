// bench_edits_main.cpp - holotrace-bench-edits: what a frame after an edit costs with frame reuse
// (RenderSettings::reuse, docs/REUSE.md §3-4) against a full frame of the same view, measured in the same run.
// Per display, --runs times: a full frame without reuse (Renderer A, the reference cost), a full frame that records
// the reuse state (Renderer B), a light edit (updateLights + the frame re-shaded from the cached primary hits) and a
// node move (Renderer::moveNodes with the node's bounds: the two-level BVH's refit + top-level update, + the partial
// re-render); the moved node alternates between two positions. Both renderers trace the two-level BVH, the layout
// holotraced gives a scene whose nodes move (until 2026-12-03 the move was a flattened rebuild, replaceSceneAfterMove).
// Reports medians of the times and of the per-run ratios, the fraction of targets re-traced and the fraction of output
// values that actually changed (their ratio: the over-invalidation of the grid masks). Ratios are given against both
// full frames: A's (no reuse) and B's own (which also records the state).
#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "bench/bench_main.h"
#include "bench/image_metrics.h"
#include "bench/output_file.h"
#include "bench/timing_series.h"
#include "camera_models/display_config.h"
#include "cli/arguments.h"
#include "common/error.h"
#include "gpu/display_camera.h"
#include "gpu/renderer.h"
#include "gpu/vulkan_context.h"
#include "scene/load_scene.h"
#include "scene/scene_edits.h"

namespace ht::bench {
namespace {

const char* const kCommand = "holotrace-bench-edits";

enum class Alternate { None, Walks, BounceHits };

struct EditOptions {
  std::vector<std::string> displays{"builtin:portrait", "bench/configs/quality-hpo-14.json"};
  std::string scene = "builtin:showcase", node = "green-sphere";
  double scale = 1.0, move = 0.05;
  std::uint32_t spp = 1, runs = 5;
  int deviceIndex = -1;
  bool fusedFloatMath = false;
  bool freshBuffers = false;  // --fresh-buffers: no Renderer::recycle
  bool convexSkip = true;     // --no-convex-skip: clears the scene's convex marks (SceneNode::convexSides)
  bool noBalls = false;       // --no-balls: the move gives the renderer its bounds alone (gpu::MovedBounds)
  double maxDirtyShare = gpu::RenderSettings{}.reuseMaxDirtyShare;
  // --alternate-walks / --alternate-bounce-hits: every other four timed moves run without the moved-instance walks
  // (Renderer::setMovedInstanceWalks) or without the cached bounce hits (Renderer::setBounceHitReuse).
  Alternate alternate = Alternate::None;
  std::optional<std::string> csvPath;
};

const std::array<cli::OptionSpec, 16> kSpecs = {{
    {"--displays", "", "LIST", "comma-separated displays (default builtin:portrait,bench/configs/quality-hpo-14.json)"},
    {"--scene", "", "SPEC", "scene (default builtin:showcase)"},
    {"--node", "", "NAME", "the node moved (default green-sphere)"},
    {"--move", "", "F", "move distance as a fraction of the scene's diagonal (default 0.05)"},
    {"--scale", "", "F", "panel / projector image size factor (default 1 = the display's own size)"},
    {"--spp", "", "N", "samples per target (default 1)"},
    {"--max-dirty-share", "", "F",
     "a move dirtying more than this share of the targets renders in full (default the renderer's, 0.75; 1: never)"},
    {"--alternate-walks", "", "",
     "every other timed move traces its rays whole instead of walking from their cached hits or recorded occlusion "
     "(Renderer::setMovedInstanceWalks), reported apart: a same-run comparison"},
    {"--alternate-bounce-hits", "", "",
     "every other timed move traces its bounce rays instead of taking their cached hits (Renderer::setBounceHitReuse), "
     "reported apart: a same-run comparison"},
    {"--no-convex-skip", "", "",
     "clear the scene's convex marks: shadow rays walk the convex node they leave (docs/BVH.md §9.6), for a "
     "comparison"},
    {"--no-balls", "", "",
     "give moves their bounds alone, not the balls around the moved node (docs/REUSE.md §4), for a comparison"},
    {"--runs", "", "N", "timed runs after one warm-up (default 5)"},
    {"--device", "", "N", "Vulkan device index (default: automatic)"},
    {"--csv", "", "PATH", "one row per display and quantity"},
    {"--fresh-buffers", "", "",
     "a new host buffer for every frame (default: frames recycle theirs, Renderer::recycle)"},
    {"--fused-math", "", "", "let the driver fuse multiplies and adds (VulkanContext::Options::fusedFloatMath)"},
}};

std::optional<EditOptions> parseOptions(std::span<const std::string> args) {
  if (cli::wantsHelp(args)) {
    std::cout << "Usage: " << kCommand << " [options]\n\n"
              << "Times a light edit and a node move with frame reuse against a full frame of the same view.\n\n"
                 "Options:\n"
              << cli::formatOptions(kSpecs);
    return std::nullopt;
  }
  const cli::ParsedArguments parsed = cli::parseArguments(kCommand, kSpecs, args);
  EditOptions o;
  if (auto list = parsed.text("--displays")) {
    o.displays.clear();
    std::stringstream stream(*list);
    for (std::string item; std::getline(stream, item, ',');) {
      if (!item.empty()) o.displays.push_back(item);
    }
    if (o.displays.empty()) throw UsageError(cli::usageMessage(kCommand, "--displays is empty"));
  }
  o.scene = parsed.textOr("--scene", o.scene);
  o.node = parsed.textOr("--node", o.node);
  o.move = parsed.numberValue("--move", 1e-4, 1.0).value_or(o.move);
  o.scale = parsed.numberValue("--scale", 0.01, 1.0).value_or(o.scale);
  o.spp = parsed.unsignedValue("--spp", 1, 4096).value_or(o.spp);
  o.maxDirtyShare = parsed.numberValue("--max-dirty-share", 0.0, 1.0).value_or(o.maxDirtyShare);
  o.runs = parsed.unsignedValue("--runs", 1, 1000).value_or(o.runs);
  if (auto device = parsed.unsignedValue("--device", 0, 255)) o.deviceIndex = int(*device);
  o.csvPath = parsed.text("--csv");
  o.fusedFloatMath = parsed.has("--fused-math");
  o.freshBuffers = parsed.has("--fresh-buffers");
  o.convexSkip = !parsed.has("--no-convex-skip");
  o.noBalls = parsed.has("--no-balls");
  if (parsed.has("--alternate-walks") && parsed.has("--alternate-bounce-hits"))
    throw UsageError(cli::usageMessage(kCommand, "--alternate-walks and --alternate-bounce-hits exclude each other"));
  if (parsed.has("--alternate-walks")) o.alternate = Alternate::Walks;
  if (parsed.has("--alternate-bounce-hits")) o.alternate = Alternate::BounceHits;
  if (o.alternate != Alternate::None && o.runs < 4)
    throw UsageError(cli::usageMessage(kCommand, "--alternate-* needs --runs 4 or more (they alternate in fours)"));
  return o;
}

// The display at `scale` of its panel (lenticular, integral) or image (pinhole; projectors without a measured
// homography) size.
DisplayConfig scaledDisplay(const std::string& spec, double scale) {
  DisplayConfig d = resolveDisplay(spec);
  auto scaled = [scale](auto& v) { v = std::max<std::uint32_t>(1, std::uint32_t(v * scale + 0.5)); };
  if (d.calibration) {
    scaled(d.calibration->screenW);
    scaled(d.calibration->screenH);
  }
  if (d.projectorArray) {
    for (ProjectorConfig& p : d.projectorArray->projectors) {
      if (p.homography) continue;  // a measured pixel mapping belongs to its image size
      scaled(p.width);
      scaled(p.height);
    }
  }
  if (d.pinhole.width) scaled(*d.pinhole.width);
  if (d.pinhole.height) scaled(*d.pinhole.height);
  return d;
}

double msSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

// Fraction of the cached primary hits on the node's triangles.
double nodeCoverage(const gpu::Renderer::ReuseSnapshot& snap, const SceneNode& node) {
  std::size_t on = 0;
  for (const gpu_shared::HtHit& h : snap.primaryHits) {
    on += h.triId >= node.firstTriangle && h.triId < node.firstTriangle + node.triangleCount ? 1 : 0;
  }
  return snap.primaryHits.empty() ? 0.0 : double(on) / double(snap.primaryHits.size());
}

struct DisplayEdits {
  std::string display;
  std::uint64_t targets = 0;
  double coverage = 0.0;  // fraction of primary samples that hit the moved node (the first recorded frame)
  TimingSeries full, recording, light, move, rebuild;
  std::vector<double> lightRatio, moveRatio, recordRatio, traced, changed;
  // --alternate-*: the moves without the walks or the cached bounce hits (the others are in `move`, `moveRatio`).
  Alternate alternate = Alternate::None;
  TimingSeries moveWhole;
  std::vector<double> moveWholeRatio;
  std::vector<gpu::StageTiming> moveWholeStages;
  std::vector<double> movedRays;  // rays the move traced (closest + any) / rays of the full frame
  std::vector<double> lightVsRecording, moveVsRecording;  // the same edits against the reusing Renderer's full frame
  std::vector<gpu::StageTiming> fullStages, lightStages, moveStages;  // medians over the runs (appendStages)
  // Host time of each frame outside its stages: RenderResult::totalMs minus the stages' sum (GPU timestamps and the
  // host readback): submissions, waits, host buffers (docs/BENCHMARKS.md "Host buffers of a frame loop").
  std::vector<double> fullOutside, lightOutside, moveOutside;
  std::uint32_t movesInFull = 0;  // timed moves that dirtied too many targets and rendered in full
};

double outsideStagesMs(const gpu::RenderResult& frame) {
  double stages = 0.0;
  for (const gpu::StageTiming& s : frame.stages) stages += s.ms;
  return frame.totalMs - stages;
}

// Per stage name, its times over the runs.
using StageRuns = std::vector<std::pair<std::string, std::vector<double>>>;

void appendStages(StageRuns& runs, const std::vector<gpu::StageTiming>& stages) {
  for (const gpu::StageTiming& s : stages) {
    auto it = std::find_if(runs.begin(), runs.end(), [&](const auto& r) { return r.first == s.name; });
    if (it == runs.end()) it = runs.insert(runs.end(), {s.name, {}});
    it->second.push_back(s.ms);
  }
}

std::vector<gpu::StageTiming> medianStages(const StageRuns& runs) {
  std::vector<gpu::StageTiming> out;
  for (const auto& [name, ms] : runs) out.push_back({name, median(ms)});
  return out;
}

DisplayEdits measure(gpu::VulkanContext& context, const std::string& spec, const EditOptions& o) {
  Scene scene = loadScene(o.scene);
  if (!o.convexSkip)
    for (SceneNode& n : scene.nodes) n.convexSides = 0;
  const std::size_t node = findNode(scene, o.node).value_or(scene.nodes.size());
  if (node == scene.nodes.size())
    throw UsageError(cli::usageMessage(kCommand, "--node: " + o.scene + " has no node '" + o.node + "'"));
  if (scene.lights.empty())
    throw UsageError(cli::usageMessage(kCommand, "--scene: " + o.scene + " has no light to edit"));
  const gpu::FrameCamera camera = gpu::makeDisplayCamera(scaledDisplay(spec, o.scale), scene.bounds()).camera;
  gpu::Renderer reference(context, scene, gpu::buildSceneBvh(scene, {}, gpu::BvhLayoutPolicy::TwoLevel));
  gpu::Renderer reusing(context, scene, gpu::buildSceneBvh(scene, {}, gpu::BvhLayoutPolicy::TwoLevel));
  const std::uint32_t movedNodes[] = {static_cast<std::uint32_t>(node)};
  gpu::RenderSettings off, on;
  off.spp = on.spp = o.spp;
  on.reuse = true;
  on.reuseMaxDirtyShare = o.maxDirtyShare;
  DisplayEdits e{spec, frameShape(camera).targets(), {}, {}, {}, {}, {}, {}, {}, {}, {}, {}};
  e.alternate = o.alternate;
  std::cout << kCommand << ": " << spec << " x " << o.scale << ", " << e.targets << " targets" << std::endl;
  const glm::dvec3 step(o.move * glm::length(scene.bounds().extent()), 0.0, 0.0);
  const float intensity = scene.lights[0].intensity;
  StageRuns stageRuns[4];  // full, light, move, move with its primary rays traced whole (--alternate-walks)
  // Run 0 is the warm-up (pipeline compilation of every variant, the partial re-render's included), not recorded.
  for (std::uint32_t run = 0; run <= o.runs; ++run) {
    // The two full frames alternate in order between runs (the first of a pair ran measurably slower here).
    gpu::RenderResult fullFrame, recorded;                        // recorded: the state the edits start from
    reusing.replaceScene(scene, gpu::BvhLayoutPolicy::TwoLevel);  // drops the state: `recorded` records it afresh
    if (run % 2) fullFrame = reference.render(camera, off);
    recorded = reusing.render(camera, on);
    if (!o.freshBuffers) reusing.recycle(std::move(recorded.rgba));
    if (run % 2 == 0) fullFrame = reference.render(camera, off);
    const double full = fullFrame.totalMs;
    if (run == 0) e.coverage = nodeCoverage(reusing.reuseSnapshot(), scene.nodes[node]);

    LightEdit dim;
    dim.intensity = intensity * (run % 2 ? 1.0 : 0.6);
    editLight(scene, 0, dim);
    auto t0 = std::chrono::steady_clock::now();
    reusing.updateLights(scene);
    gpu::RenderResult lit = reusing.render(camera, on);
    const double light = msSince(t0);
    if (lit.reuse != gpu::FrameReuse::CachedPrimaryHits) throw GpuError("the light edit did not reuse the cache");

    const Bounds3 before = nodeWorldBounds(scene, node);
    const auto ball = [&] { return o.noBalls ? kNoBall : nodeWorldBall(scene, node); };  // --no-balls: none
    const glm::vec4 beforeBall = ball();
    glm::dmat4 world = scene.nodes[node].world;
    world[3] += glm::dvec4(run % 2 ? -step : step, 0.0);
    setNodeWorldMatrix(scene, o.node, world);
    // (period 4: each setting gets both move directions and both orders of the full frames)
    const bool walks = o.alternate == Alternate::None || (run - 1) % 4 < 2;
    reusing.setMovedInstanceWalks(walks || o.alternate != Alternate::Walks);
    reusing.setBounceHitReuse(walks || o.alternate != Alternate::BounceHits);
    t0 = std::chrono::steady_clock::now();
    reusing.moveNodes(scene, movedNodes, gpu::MovedBounds{before, nodeWorldBounds(scene, node), beforeBall, ball()});
    const double rebuild = msSince(t0);
    gpu::RenderResult moved = reusing.render(camera, on);
    const double move = msSince(t0);
    // (a move that dirties most of the targets renders the frame in full, docs/REUSE.md §4)
    if (moved.reuse != gpu::FrameReuse::PartialRetrace && moved.reuse != gpu::FrameReuse::None)
      throw GpuError("the node move re-shaded cached hits");
    const double changed = changedValueFraction(lit.rgba, moved.rgba);
    if (!o.freshBuffers) {  // as a frame loop does once it has shown them
      reference.recycle(std::move(fullFrame.rgba));
      reusing.recycle(std::move(lit.rgba));
      reusing.recycle(std::move(moved.rgba));
    }
    if (run == 0) continue;

    e.full.ms.push_back(full);
    e.recording.ms.push_back(recorded.totalMs);
    e.light.ms.push_back(light);
    e.recordRatio.push_back(recorded.totalMs / full);
    e.lightRatio.push_back(light / full);
    e.lightVsRecording.push_back(light / recorded.totalMs);
    e.fullOutside.push_back(outsideStagesMs(fullFrame));
    e.lightOutside.push_back(outsideStagesMs(lit));
    appendStages(stageRuns[0], fullFrame.stages);
    appendStages(stageRuns[1], lit.stages);
    if (!walks) {
      e.moveWhole.ms.push_back(move);
      e.moveWholeRatio.push_back(move / full);
      appendStages(stageRuns[3], moved.stages);
      continue;
    }
    if (moved.reuse == gpu::FrameReuse::None) ++e.movesInFull;
    e.rebuild.ms.push_back(rebuild);
    e.move.ms.push_back(move);
    e.moveRatio.push_back(move / full);
    e.moveVsRecording.push_back(move / recorded.totalMs);
    e.traced.push_back(double(moved.tracedTargets) / double(e.targets));
    e.movedRays.push_back(double(moved.raysTraced) / double(std::max<std::uint64_t>(fullFrame.raysTraced, 1)));
    e.changed.push_back(changed);
    e.moveOutside.push_back(outsideStagesMs(moved));
    appendStages(stageRuns[2], moved.stages);
  }
  e.fullStages = medianStages(stageRuns[0]);
  e.lightStages = medianStages(stageRuns[1]);
  e.moveStages = medianStages(stageRuns[2]);
  e.moveWholeStages = medianStages(stageRuns[3]);
  return e;
}

void print(const DisplayEdits& e) {
  std::printf("\n%s (%llu targets; the moved node covers %.4f of the primary samples)\n", e.display.c_str(),
              static_cast<unsigned long long>(e.targets), e.coverage);
  std::printf("  full frame, no reuse:         %9.1f ms\n", e.full.medianMs());
  std::printf("  full frame, recording reuse:  %9.1f ms   ratio %.3f\n", e.recording.medianMs(), median(e.recordRatio));
  std::printf("  light edit (update + frame):  %9.1f ms   ratio %.3f (vs recording %.3f)\n", e.light.medianMs(),
              median(e.lightRatio), median(e.lightVsRecording));
  std::printf("  node move (update + frame):   %9.1f ms   ratio %.3f (vs recording %.3f)   (BVH update %.1f ms)\n",
              e.move.medianMs(), median(e.moveRatio), median(e.moveVsRecording), e.rebuild.medianMs());
  std::printf("  re-traced targets %.4f, changed output values %.4f, rays traced %.4f of the full frame's\n",
              median(e.traced), median(e.changed), median(e.movedRays));
  if (e.movesInFull > 0) {
    std::printf("  %u of %zu moves dirtied too many targets for a partial re-render and rendered in full\n",
                e.movesInFull, e.move.ms.size());
  }
  if (!e.moveWhole.ms.empty()) {
    const bool walks = e.alternate == Alternate::Walks;
    std::printf("  node move, %s: %9.1f ms   ratio %.3f   (%s: %.3f, medians of %zu / %zu)\n",
                walks ? "rays traced whole" : "bounce rays traced", e.moveWhole.medianMs(), median(e.moveWholeRatio),
                walks ? "walks / whole" : "cached / traced", median(e.moveRatio) / median(e.moveWholeRatio),
                e.move.ms.size(), e.moveWhole.ms.size());
  }
  std::printf("  stages, medians of the runs (GPU ms; readback: host):");
  for (const auto* stages : {&e.fullStages, &e.lightStages, &e.moveStages, &e.moveWholeStages}) {
    if (stages->empty()) continue;
    std::printf("\n   %s", stages == &e.fullStages    ? "full "
                           : stages == &e.lightStages ? "light"
                           : stages == &e.moveStages  ? "move "
                                                      : "off  ");
    for (const gpu::StageTiming& s : *stages) std::printf(" %s %.1f", s.name.c_str(), s.ms);
  }
  std::printf("\n  host time outside the stages (ms, medians): full %.1f, light %.1f, move %.1f\n",
              median(e.fullOutside), median(e.lightOutside), median(e.moveOutside));
}

std::string csvRows(const DisplayEdits& e) {
  std::ostringstream csv;
  const std::pair<const char*, double> rows[] = {{"full_ms", e.full.medianMs()},
                                                 {"recording_ms", e.recording.medianMs()},
                                                 {"light_edit_ms", e.light.medianMs()},
                                                 {"node_move_ms", e.move.medianMs()},
                                                 {"bvh_rebuild_ms", e.rebuild.medianMs()},
                                                 {"ratio_recording", median(e.recordRatio)},
                                                 {"ratio_light_edit", median(e.lightRatio)},
                                                 {"ratio_node_move", median(e.moveRatio)},
                                                 {"ratio_light_edit_vs_recording", median(e.lightVsRecording)},
                                                 {"ratio_node_move_vs_recording", median(e.moveVsRecording)},
                                                 {"node_coverage", e.coverage},
                                                 {"retraced_fraction", median(e.traced)},
                                                 {"move_rays_fraction", median(e.movedRays)},
                                                 {"changed_fraction", median(e.changed)},
                                                 {"full_outside_stages_ms", median(e.fullOutside)},
                                                 {"light_edit_outside_stages_ms", median(e.lightOutside)},
                                                 {"node_move_outside_stages_ms", median(e.moveOutside)}};
  for (const auto& [name, value] : rows) csv << e.display << "," << name << "," << value << "\n";
  if (!e.moveWhole.ms.empty()) {  // --alternate-*
    const std::string off = e.alternate == Alternate::Walks ? "primary_whole" : "bounces_traced";
    csv << e.display << ",node_move_" << off << "_ms," << e.moveWhole.medianMs() << "\n";
    csv << e.display << ",ratio_node_move_" << off << "," << median(e.moveWholeRatio) << "\n";
  }
  return csv.str();
}

int run(const EditOptions& o) {
  gpu::VulkanContext context({o.deviceIndex, false, false, o.fusedFloatMath});
  std::string csv = "display,quantity,value\n";
  for (const std::string& display : o.displays) {
    const DisplayEdits e = measure(context, display, o);
    print(e);
    csv += csvRows(e);
  }
  if (o.csvPath) writeTextFile(*o.csvPath, csv);
  return 0;
}

}  // namespace
}  // namespace ht::bench

int main(int argc, char** argv) {
  // parseOptions prints its own --help text.
  return ht::bench::benchMain(
      argc, argv, ht::bench::kCommand,
      [](const std::vector<std::string>& a, std::string*) { return ht::bench::parseOptions(a); },
      [](const auto& options) { return ht::bench::run(options); });
}
