// frame_job.h - one display frame of one scene session, rendered on the render worker.
#pragma once
#include <cstdint>
#include <memory>
#include <string>

#include "camera_models/display_config.h"
#include "gpu/display_camera.h"
#include "gpu/renderer.h"
#include "server/display_registry.h"
#include "server/render_worker.h"
#include "server/scene_library.h"

namespace ht::server {

class DistributedFrames;

struct FrameJob {
  std::shared_ptr<const SceneSession> session;
  std::shared_ptr<const RegisteredDisplay> display;
  std::uint32_t spp = 0;        // 0 = display default
  std::uint32_t refineSpp = 0;  // adaptive refinement (gpu::RenderSettings::refineSpp); 0 = off
  float refineContrast = gpu::RenderSettings{}.refineContrast;
  std::uint32_t seed = 0;
  bool reuse = false;                              // RenderRequest.reuse_after_edits (gpu::RenderSettings::reuse)
  gpu::CameraPath path = gpu::CameraPath::Native;  // RenderRequest.quilt
  DistributedFrames* cluster = nullptr;            // set under mpirun: every rank renders a share (docs/CLUSTER.md §8)
};

// What a frame of `display` is (views of width x height), independent of any scene. Throws ConfigError for
// combinations that do not exist (quilt of a non-lenticular display).
gpu::FrameShape displayFrameShape(const RegisteredDisplay& display, gpu::CameraPath path = gpu::CameraPath::Native);

// The display with the session's UpdateScene camera placement and tracked observer applied.
DisplayConfig displayForSession(const DisplayConfig& display, const SceneSession& session);

// The camera a job renders (the session's display, placed against its scene).
gpu::DisplayCamera jobCamera(const FrameJob& job);

// Queues the frame for `client` and waits for it. Throws what the worker or renderer threw. `recycled`: the pixels of
// the caller's previous frame, done with, which the session's renderer may write this one into instead of a new
// buffer (gpu::Renderer::recycle, on the worker thread; docs/BENCHMARKS.md "Host buffers of a frame loop"); taken.
gpu::RenderResult renderFrameJob(RenderWorker& worker, const std::string& client, const FrameJob& job,
                                 std::vector<float>* recycled = nullptr);

// One progressive frame of `job` (gpu/accumulator.h): job.spp (or the display's) more samples into `accumulator`,
// on the worker. The job's refinement settings are ignored (the accumulator's policy places samples). The session's
// content must have a Renderer (not a quilt image).
gpu::RenderResult accumulateFrameJob(RenderWorker& worker, const std::string& client, const FrameJob& job,
                                     gpu::Accumulator& accumulator);

}  // namespace ht::server
