// cluster_render.h - a sequence of frames (`holotrace render` under mpirun: one; `holotrace capture`: N) rendered by
// the ranks of an MPI job (cluster/, docs/CLUSTER.md), or by one plain process through the same path. Every rank
// resolves the display itself, rank 0 loads the scene and broadcasts it, the ranks check they agree
// (cluster/rank_identity.h), build their own BVH, and rank 0 hands out work units and writes the frames.
#pragma once
#include <cstdint>
#include <functional>
#include <ostream>
#include <string>

#include "camera_models/display_config.h"
#include "cli/render_options.h"
#include "cluster/communicator.h"
#include "frame_io/frame_package.h"
#include "gpu/display_camera.h"
#include "gpu/renderer.h"
#include "scene/scene.h"

namespace ht::cli {

struct FrameSequence {
  std::uint32_t frames = 1;  // frame f is rendered with seed options.seed + f
  bool ranksWrite = false;   // each rank writes the frames it renders (a shared output root); else rank 0 writes all
  // Before any rendering, on the ranks that write: create and check the outputs (throws to stop the job).
  std::function<void(const DisplayConfig& display, const gpu::DisplayCamera& camera)> prepare;
  // Writes frame `frame` whole (through frame_io's packageFrame, atomically); `out` is the rank's report stream.
  std::function<void(std::ostream& out, std::uint32_t frame, const gpu::RenderResult& result,
                     const frame_io::FrameDisplay& display)>
      write;
};

// Joins the MPI job this process was launched in (or runs alone), renders the sequence and returns the exit code.
// An error on any rank ends the job on every rank (MPI_Abort with the error's exit code) after printing it; ranks
// that disagree at the start-up check all exit with kExitUsage. Only rank 0 prints reports to `out`.
int runFrameSequence(const RenderOptions& options, const FrameSequence& sequence, std::ostream& out);

// Joins the job (or runs alone) and runs `body` on this rank. An error ends the job on every rank (MPI_Abort with
// the error's exit code) after printing it with rankPrefix(); a RankMismatchError returns kExitUsage on every rank.
// A single process lets errors through to runCli.
int runOnEveryRank(const std::function<int(cluster::Communicator& comm)>& body);
// "holotrace: rank R of N: " in a job of several ranks, "holotrace: " alone.
std::string rankPrefix(const cluster::Communicator& comm);

// Rank 0 loads the scene and broadcasts its bytes; every other rank decodes them (no shared filesystem needed).
struct SharedScene {
  Scene scene;
  std::string digest;  // SHA-256 of the bytes, for the start-up check
  double loadMs = 0.0;
};
SharedScene shareScene(cluster::Communicator& comm, const std::string& spec);

}  // namespace ht::cli
