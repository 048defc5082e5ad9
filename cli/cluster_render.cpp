// cluster_render.cpp - see cluster_render.h.
#include "cli/cluster_render.h"

#include <chrono>
#include <cstdio>
#include <iostream>
#include <memory>
#include <sstream>

#include "cli/cli_app.h"
#include "cli/render_command.h"
#include "cli/render_report.h"
#include "cluster/cluster_error.h"
#include "cluster/communicator.h"
#include "cluster/content_hash.h"
#include "cluster/frame_assembly.h"
#include "cluster/rank_identity.h"
#include "cluster/scene_bytes.h"
#include "cluster/work_dispatch.h"
#include "cluster/work_plan.h"
#include "common/error.h"
#include "frame_io/ray_table_exr.h"
#include "gpu/display_camera.h"
#include "gpu/vulkan_context.h"

namespace ht::cli {
namespace {

using Clock = std::chrono::steady_clock;

double msSince(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

void printClusterReport(std::ostream& out, const cluster::DispatchReport& report, std::size_t units) {
  out << "cluster: " << report.ranks.size() << (report.ranks.size() == 1 ? " rank, " : " ranks, ") << units
      << " work units, " << formatMs(report.wallMs) << "\n";
  for (std::size_t r = 0; r < report.ranks.size(); ++r) {
    const cluster::RankWork& w = report.ranks[r];
    out << "  rank " << r << ": " << w.units << " units, busy " << formatMs(w.busyMs) << ", idle "
        << formatMs(std::max(0.0, report.wallMs - w.busyMs)) << "\n";
  }
  char gather[96];
  std::snprintf(gather, sizeof gather, "  gathered %.2f MiB in %s\n", report.gatherBytes / 1048576.0,
                formatMs(report.gatherMs).c_str());
  out << gather;
}

// Everything a rank does for the sequence. Throws on any failure (runFrameSequence ends the job).
int renderSequenceOnRank(cluster::Communicator& comm, const RenderOptions& options, const FrameSequence& sequence,
                         std::ostream& out) {
  const auto start = Clock::now();
  const bool root = comm.rank() == 0;
  std::ostream silent(nullptr);
  std::ostream& log = root ? out : silent;

  const DisplayConfig display = resolveDisplay(options.displaySpec);
  log << "display: " << display.name << " (" << displayModelName(display.model) << ", " << options.displaySpec << ")\n";
  const SharedScene shared = shareScene(comm, options.sceneSpec);
  std::shared_ptr<const RayTable> rayTable;
  if (display.model == DisplayModel::RayTable) {
    rayTable = std::make_shared<RayTable>(frame_io::loadDisplayRayTable(display));
  }
  const gpu::DisplayCamera camera = makeDisplayCamera(display, shared.scene.bounds(), options.cameraPath, rayTable);
  if (root || sequence.ranksWrite) sequence.prepare(display, camera);
  gpu::RenderSettings settings = makeRenderSettings(options, display);
  settings.progress = nullptr;
  cluster::checkRankIdentities(comm, {cluster::buildId(), cluster::displayDigest(display.name, camera), shared.digest,
                                      cluster::settingsDigest(settings)});

  gpu::VulkanContext context({options.deviceIndex, options.validation});
  if (root) printDevice(log, context.device());
  const auto renderer = buildRenderer(log, context, shared.scene, shared.loadMs);
  const cluster::WorkGrain grain = sequence.ranksWrite      ? cluster::WorkGrain::WholeFrames
                                   : settings.refineSpp > 0 ? cluster::WorkGrain::WholeViews
                                                            : cluster::WorkGrain::Auto;
  const std::vector<cluster::WorkUnit> units = cluster::planWork(camera.shape, sequence.frames, comm.size(), grain);
  const frame_io::FrameDisplay frameDisplay{display, camera.quilt};
  const gpu::FrameShape& shape = camera.shape;
  log << "render: " << sequence.frames << (sequence.frames == 1 ? " frame" : " frames") << " of " << shape.views
      << (shape.views == 1 ? " view" : " views") << " of " << shape.width << "x" << shape.height << ", spp "
      << settings.spp << ", seed " << settings.seed << ", " << units.size() << " work units over " << comm.size()
      << (comm.size() == 1 ? " rank\n" : " ranks\n");

  const auto renderUnit = [&](const cluster::WorkUnit& unit) -> std::vector<float> {
    gpu::RenderSettings unitSettings = settings;
    unitSettings.seed = settings.seed + unit.frame;
    unitSettings.region = unit.region;
    gpu::RenderResult result = renderer->render(camera.camera, unitSettings);
    if (result.nonFiniteSamples > 0) {
      std::cerr << "holotrace: rank " << comm.rank() << ": warning: " << result.nonFiniteSamples
                << " samples were NaN/Inf and were written as 0 (a renderer bug)\n";
    }
    if (!sequence.ranksWrite) return std::move(result.rgba);
    std::ostringstream lines;  // a worker's own report, printed whole
    sequence.write(lines, unit.frame, result, frameDisplay);
    if (!root)
      std::cout << lines.str() << std::flush;
    else
      log << lines.str();
    return {};
  };
  cluster::FrameAssembly assembly(shape, units);
  const auto collect = [&](std::size_t unit, std::vector<float>&& rgba) {
    if (sequence.ranksWrite) return;
    if (const auto frame = assembly.place(unit, rgba)) sequence.write(log, *frame, assembly.take(*frame), frameDisplay);
  };
  const cluster::DispatchReport report = cluster::dispatchWork(comm, units, renderUnit, collect);
  if (root) printClusterReport(log, report, units.size());
  log << "total " << formatMs(msSince(start)) << "\n";
  return kExitOk;
}

}  // namespace

SharedScene shareScene(cluster::Communicator& comm, const std::string& spec) {
  const auto start = Clock::now();
  SharedScene shared;
  std::vector<std::uint8_t> bytes;
  if (comm.rank() == 0) {
    shared.scene = loadScene(spec);
    bytes = cluster::encodeScene(shared.scene);
  }
  comm.broadcast(bytes, 0);
  if (comm.rank() != 0) shared.scene = cluster::decodeScene(bytes);
  shared.digest = cluster::ContentHash().add(bytes).hex();
  shared.loadMs = msSince(start);
  return shared;
}

std::string rankPrefix(const cluster::Communicator& comm) {
  if (comm.size() == 1) return "holotrace: ";
  return "holotrace: rank " + std::to_string(comm.rank()) + " of " + std::to_string(comm.size()) + ": ";
}

int runOnEveryRank(const std::function<int(cluster::Communicator& comm)>& body) {
  const std::unique_ptr<cluster::Communicator> comm = cluster::Communicator::forThisProcess();
  if (comm->size() == 1) return body(*comm);  // runCli maps errors
  try {
    return body(*comm);
  } catch (const cluster::RankMismatchError& e) {
    std::cerr << rankPrefix(*comm) << "error: " << e.what() << "\n";
    return kExitUsage;  // every rank got the same verdict: all end cleanly
  } catch (const UsageError& e) {
    std::cerr << rankPrefix(*comm) << e.what() << "\n" << std::flush;
    comm->abort(kExitUsage);
  } catch (const std::exception& e) {
    std::cerr << rankPrefix(*comm) << "error: " << e.what() << "\n" << std::flush;
    comm->abort(kExitError);
  }
  return kExitError;  // not reached: abort() ends the process
}

int runFrameSequence(const RenderOptions& options, const FrameSequence& sequence, std::ostream& out) {
  return runOnEveryRank(
      [&](cluster::Communicator& comm) { return renderSequenceOnRank(comm, options, sequence, out); });
}

}  // namespace ht::cli
