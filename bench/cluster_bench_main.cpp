// cluster_bench_main.cpp - holotrace-bench-cluster: the terms of the cluster cost model (docs/CLUSTER.md §5,
// docs/BENCHMARKS.md "Cluster"), measured under `mpirun -np N` (or alone, as one rank):
//   per frame of a multi-view display (default the 70-projector wall, its projector images scaled by --image-scale)
//   with rank 0's dynamic hand-out and with static blocks: wall time, every rank's busy and idle time, the load
//   imbalance (slowest rank's busy / mean busy), the pixel bytes gathered to rank 0 and the time receiving them;
//   the render time of each view (rank 0's units; all of them at -np 1); rank 0's PNG packaging time per frame;
//   MPI_Barrier and a 256-byte frame-state broadcast (medians of 200); 16 MiB from rank 1 to rank 0 with both idle
//   (the gather bandwidth without render contention, median of 5); the scene broadcast at start.
// Medians over --frames frames after one warm-up frame (which compiles the kernels). Only rank 0 prints.
//
// Usage: mpirun -np N holotrace-bench-cluster [--display SPEC] [--scene SPEC] [--image-scale X] [--spp N]
//                                             [--depth N] [--frames N] [--device N]
#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <numeric>
#include <string>
#include <vector>

#include "bench/timing_series.h"
#include "camera_models/display_config.h"
#include "cli/arguments.h"
#include "cluster/communicator.h"
#include "cluster/frame_assembly.h"
#include "cluster/scene_bytes.h"
#include "cluster/work_dispatch.h"
#include "cluster/work_plan.h"
#include "common/error.h"
#include "frame_io/frame_package.h"
#include "gpu/display_camera.h"
#include "gpu/renderer.h"
#include "gpu/vulkan_context.h"

namespace ht::bench {
namespace {

using Clock = std::chrono::steady_clock;
const char* const kProgram = "holotrace-bench-cluster";

const std::array<cli::OptionSpec, 7> kSpecs = {{
    {"--display", "", "SPEC", "multi-view display (default builtin:holovizio-wall-70)"},
    {"--scene", "", "SPEC", "scene (default builtin:showcase)"},
    {"--image-scale", "", "X", "scale of each view's width and height, 0.01-1 (default 0.125: 128x72 per projector)"},
    {"--spp", "", "N", "samples per pixel (default 1)"},
    {"--depth", "", "N", "specular bounces (default 2)"},
    {"--frames", "", "N", "measured frames per assignment, >= 5 (default 5)"},
    {"--device", "", "N", "Vulkan device index"},
}};

struct Options {
  std::string display = "builtin:holovizio-wall-70";
  std::string scene = "builtin:showcase";
  double imageScale = 0.125;
  std::uint32_t spp = 1, depth = 2, frames = 5;
  int device = -1;
};

Options parseOptions(int argc, char** argv) {
  const std::vector<std::string> args(argv + 1, argv + argc);
  if (cli::wantsHelp(args)) {
    std::cout << "Usage: mpirun -np N " << kProgram << " [options]\n\n" << cli::formatOptions(kSpecs);
    std::exit(0);
  }
  const cli::ParsedArguments parsed = cli::parseArguments(kProgram, kSpecs, args);
  Options o;
  o.display = parsed.textOr("--display", o.display);
  o.scene = parsed.textOr("--scene", o.scene);
  o.imageScale = parsed.numberValue("--image-scale", 0.01, 1.0).value_or(o.imageScale);
  o.spp = parsed.unsignedValue("--spp", 1, 4096).value_or(o.spp);
  o.depth = parsed.unsignedValue("--depth", 0, 32).value_or(o.depth);
  o.frames = parsed.unsignedValue("--frames", 5, 1000).value_or(o.frames);
  if (const auto device = parsed.unsignedValue("--device", 0, 255)) o.device = static_cast<int>(*device);
  return o;
}

double msSince(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

DisplayConfig scaledDisplay(const Options& o) {
  DisplayConfig display = resolveDisplay(o.display);
  if (display.model != DisplayModel::ProjectorArray) {
    throw UsageError(std::string(kProgram) + ": --display '" + o.display + "' is not a projector array");
  }
  for (ProjectorConfig& projector : display.projectorArray->projectors) {
    if (projector.homography) {
      throw UsageError(std::string(kProgram) + ": --display '" + o.display +
                       "' maps its projector pixels by homographies, which --image-scale cannot scale; use 1");
    }
    projector.width = std::max(1u, static_cast<std::uint32_t>(projector.width * o.imageScale));
    projector.height = std::max(1u, static_cast<std::uint32_t>(projector.height * o.imageScale));
  }
  return display;
}

// One frame's measurements on rank 0.
struct FrameSample {
  double wallMs = 0.0, gatherMs = 0.0, encodeMs = 0.0;
  std::uint64_t gatherBytes = 0;
  std::vector<double> busyMs;  // per rank
};

double imbalance(const std::vector<double>& busy) {
  const double mean = std::accumulate(busy.begin(), busy.end(), 0.0) / static_cast<double>(busy.size());
  return mean > 0.0 ? *std::max_element(busy.begin(), busy.end()) / mean : 1.0;
}

void printAssignment(const char* name, const std::vector<FrameSample>& samples, int ranks) {
  std::vector<double> wall, gather, gatherMiB, encode, ratio;
  std::vector<std::vector<double>> busy(static_cast<std::size_t>(ranks)), idle(static_cast<std::size_t>(ranks));
  for (const FrameSample& s : samples) {
    wall.push_back(s.wallMs);
    gather.push_back(s.gatherMs);
    gatherMiB.push_back(s.gatherBytes / 1048576.0);
    encode.push_back(s.encodeMs);
    ratio.push_back(imbalance(s.busyMs));
    for (std::size_t r = 0; r < s.busyMs.size(); ++r) {
      busy[r].push_back(s.busyMs[r]);
      idle[r].push_back(std::max(0.0, s.wallMs - s.busyMs[r]));
    }
  }
  std::printf(
      "%-8s frame wall %9.1f ms  imbalance (max/mean busy) %.3f  gather %.2f MiB in %.2f ms  "
      "rank-0 PNG packaging %.1f ms\n",
      name, median(wall), median(ratio), median(gatherMiB), median(gather), median(encode));
  for (int r = 0; r < ranks; ++r) {
    std::printf("         rank %d busy %9.1f ms  idle %8.1f ms\n", r, median(busy[static_cast<std::size_t>(r)]),
                median(idle[static_cast<std::size_t>(r)]));
  }
}

// Median microseconds of `runs` calls of `step` (after one).
template <typename Step>
double medianMicros(int runs, const Step& step) {
  step();
  std::vector<double> us;
  for (int i = 0; i < runs; ++i) {
    const auto start = Clock::now();
    step();
    us.push_back(msSince(start) * 1e3);
  }
  return median(us);
}

int run(const Options& o) {
  const auto comm = cluster::Communicator::forThisProcess();
  const bool root = comm->rank() == 0;
  const DisplayConfig display = scaledDisplay(o);
  std::vector<std::uint8_t> sceneBytes;
  Scene scene;
  if (root) sceneBytes = cluster::encodeScene(scene = loadScene(o.scene));
  comm->barrier();
  const auto bcastStart = Clock::now();
  comm->broadcast(sceneBytes, 0);
  const double bcastMs = msSince(bcastStart);
  if (!root) scene = cluster::decodeScene(sceneBytes);
  const gpu::DisplayCamera camera = gpu::makeDisplayCamera(display, scene.bounds());
  gpu::VulkanContext context({o.device, false});
  gpu::Renderer renderer(context, scene);
  gpu::RenderSettings settings;
  settings.spp = o.spp;
  settings.maxDepth = o.depth;
  const std::vector<cluster::WorkUnit> units =
      cluster::planWork(camera.shape, 1, comm->size(), cluster::WorkGrain::Auto);

  std::vector<double> viewMs;  // rank 0's units
  const auto render = [&](const cluster::WorkUnit& unit) {
    gpu::RenderSettings s = settings;
    s.region = unit.region;
    const auto start = Clock::now();
    std::vector<float> rgba = renderer.render(camera.camera, s).rgba;
    if (root) viewMs.push_back(msSince(start));
    return rgba;
  };
  const auto frame = [&](cluster::Assignment assignment, bool encode) {
    cluster::FrameAssembly assembly(camera.shape, units);
    gpu::RenderResult whole;
    comm->barrier();
    const cluster::DispatchReport report = cluster::dispatchWork(
        *comm, units, render,
        [&](std::size_t unit, std::vector<float>&& rgba) {
          if (const auto done = assembly.place(unit, rgba)) whole = assembly.take(*done);
        },
        assignment);
    FrameSample sample{report.wallMs, report.gatherMs, 0.0, report.gatherBytes, {}};
    for (const cluster::RankWork& w : report.ranks) sample.busyMs.push_back(w.busyMs);
    if (root && encode) {
      const auto start = Clock::now();
      frame_io::packageFrame({whole.width, whole.height, whole.views, whole.rgba}, {display, camera.quilt},
                             frame_io::ViewLayout::Views, frame_io::FrameFormat::Png, "wall.png");
      sample.encodeMs = msSince(start);
    }
    return sample;
  };

  frame(cluster::Assignment::Dynamic, false);  // warm-up: kernels compiled on every rank
  viewMs.clear();
  std::vector<FrameSample> dynamicFrames, staticFrames;
  for (std::uint32_t f = 0; f < o.frames; ++f) {
    dynamicFrames.push_back(frame(cluster::Assignment::Dynamic, true));
    staticFrames.push_back(frame(cluster::Assignment::Static, false));
  }
  const double barrierUs = medianMicros(200, [&] { comm->barrier(); });
  std::vector<std::uint8_t> state(256, 0);
  const double stateUs = medianMicros(200, [&] { comm->broadcast(state, 0); });
  // Rank 0's receive bandwidth with every rank idle (the gather's beta without render contention): rank 1 sends
  // 16 MiB after a barrier, median of 5.
  std::vector<std::uint8_t> block(16u << 20, 1);
  std::vector<double> transferMs;
  for (int i = 0; i < 5 && comm->size() > 1; ++i) {
    comm->barrier();
    const auto start = Clock::now();
    if (root)
      comm->receive(1, 7, block);
    else if (comm->rank() == 1)
      comm->send(0, 7, block);
    transferMs.push_back(msSince(start));
  }
  if (!root) return 0;

  const gpu::FrameShape& shape = camera.shape;
  std::printf(
      "%s: %d rank(s), %s: %u views of %ux%u (image scale %.3f), scene %s, spp %u, depth %u, %u frames "
      "after 1 warm-up\n",
      kProgram, comm->size(), display.name.c_str(), shape.views, shape.width, shape.height, o.imageScale,
      o.scene.c_str(), o.spp, o.depth, o.frames);
  std::printf("scene broadcast %.2f MiB in %.2f ms; MPI_Barrier %.2f us; 256-byte broadcast %.2f us (medians of 200)\n",
              sceneBytes.size() / 1048576.0, bcastMs, barrierUs, stateUs);
  if (!transferMs.empty()) {
    const double ms = median(transferMs);
    std::printf("16 MiB rank 1 -> rank 0, both idle: %.2f ms (%.2f GiB/s, median of 5)\n", ms,
                16.0 / 1024.0 / (ms / 1e3));
  }
  std::vector<double> sorted = viewMs;
  std::sort(sorted.begin(), sorted.end());
  if (!sorted.empty()) {
    std::printf("view render time on rank 0 (%zu views): min %.2f ms, median %.2f ms, max %.2f ms, mean %.2f ms\n",
                sorted.size(), sorted.front(), median(sorted), sorted.back(),
                std::accumulate(sorted.begin(), sorted.end(), 0.0) / static_cast<double>(sorted.size()));
  }
  printAssignment("dynamic", dynamicFrames, comm->size());
  printAssignment("static", staticFrames, comm->size());
  return 0;
}

}  // namespace
}  // namespace ht::bench

int main(int argc, char** argv) {
  try {
    return ht::bench::run(ht::bench::parseOptions(argc, argv));
  } catch (const ht::UsageError& e) {
    std::cerr << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "holotrace-bench-cluster: error: " << e.what() << "\n";
    return 1;
  }
}
