// cluster_job.h - what rank 0 of holotraced under mpirun sends every other rank for one frame (docs/CLUSTER.md §8):
// the scene version to render (with the scene's bytes when the ranks do not have that version yet, and the versions
// they may forget), the display, the session's camera placement, the camera path and the render settings; or "stop".
// The ranks rebuild the camera from these with the same functions as rank 0 (server/frame_job.h) and compare its
// digest with rank 0's, so a display config changed on one node is an error, never a silently different frame.
#pragma once
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "camera_models/display_config.h"
#include "cluster/work_plan.h"
#include "common/bounds3.h"
#include "gpu/display_camera.h"
#include "gpu/renderer.h"

namespace ht::server {

// Point-to-point tag of the wake-up that precedes each job's broadcast (cluster/work_dispatch.cpp uses 101-104).
inline constexpr int kClusterJobTag = 201;

struct ClusterJob {
  enum class Kind : std::uint32_t { Frame = 1, Stop = 2 };
  Kind kind = Kind::Frame;
  std::uint64_t sceneVersion = 0;
  std::vector<std::uint8_t> sceneBytes;     // cluster/scene_bytes.h; empty when the ranks hold sceneVersion
  std::vector<std::uint64_t> dropVersions;  // scene versions rank 0 no longer holds
  Bounds3 loadBounds;                       // SceneContent::loadBounds (auto camera placement)
  std::string displayId;
  std::string cameraDigest;                // cluster::displayDigest of the camera rank 0 renders
  std::optional<glm::dvec3> cameraTarget;  // SceneSession::cameraOverride
  std::optional<double> cameraSize;
  std::optional<double> observerDistance, observerHeight;
  gpu::CameraPath path = gpu::CameraPath::Native;
  gpu::RenderSettings settings;  // region and progress are not sent
};

// The work units of one frame, cut the same way on every rank (cluster/work_plan.h: whole views when adaptive
// refinement compares neighbour rows).
std::vector<cluster::WorkUnit> clusterFrameUnits(const gpu::FrameShape& shape, const gpu::RenderSettings& settings,
                                                 int ranks);
// The pixels of one unit (RGBA floats of its views and rows), as every rank renders them.
std::vector<float> renderClusterUnit(gpu::Renderer& renderer, const gpu::DisplayCamera& camera,
                                     const gpu::RenderSettings& settings, const cluster::WorkUnit& unit);

std::vector<std::uint8_t> encodeClusterJob(const ClusterJob& job);
// Throws cluster::ClusterError when the bytes are not a job of this build.
ClusterJob decodeClusterJob(std::span<const std::uint8_t> bytes);

}  // namespace ht::server
