// scene_rpcs.cpp - ListDisplays, GetDisplay, LoadScene, UploadScene, UpdateScene, Status, UnloadScene.
#include <unistd.h>

#include <cmath>

#include "bvh/bvh_layout_choice.h"
#include "frame_io/quilt_file.h"
#include "scene/scene_edits.h"
#include "scene/scene_source.h"
#include "server/cluster_status.h"
#include "server/display_messages.h"
#include "server/holotrace_service.h"
#include "server/path_rules.h"
#include "server/present_status.h"
#include "server/process_stats.h"
#include "server/status_mapping.h"

namespace ht::server {
namespace v1 = holotrace::v1;
namespace {

void fillHandle(const SceneSession& session, v1::SceneHandle& out) {
  out.set_scene_id(session.id);
  out.set_triangles(session.content->scene.triangleCount());
  if (session.content->renderer) {  // a quilt image has none (server/quilt_content.h)
    out.set_bvh_build_ms(session.content->renderer->bvhReport().buildMs);
    out.set_sah_cost(session.content->renderer->bvhReport().sahCost);
  }
  out.set_reused(session.reused);
  out.set_load_ms(session.content->loadMs);
  for (const SceneNode& node : session.content->scene.nodes) out.add_nodes(node.name);
  out.set_lights(static_cast<std::uint32_t>(session.content->scene.lights.size()));
}

void checkSceneExtension(const std::string& fileName) {
  checkFileNameComponent("info.file_name", fileName);
  const auto dot = fileName.rfind('.');
  const std::string ext = dot == std::string::npos ? "" : fileName.substr(dot);
  if (ext != ".glb" && ext != ".gltf" && ext != ".obj" && ext != ".off" && !frame_io::isQuiltImageFile(fileName)) {
    throw BadRequest("info.file_name",
                     "'" + fileName +
                         "' must end in .glb, .gltf, .obj or .off (a scene), or .png or .exr (a quilt "
                         "image named NAME_qs{columns}x{rows}a{aspect}.png)");
  }
}

struct NodeEdit {
  std::string name;
  glm::dmat4 world{1.0};
};

std::vector<NodeEdit> readNodeEdits(const v1::UpdateSceneRequest& request) {
  std::vector<NodeEdit> edits;
  for (int i = 0; i < request.nodes_size(); ++i) {
    const v1::NodeTransform& n = request.nodes(i);
    const std::string field = "nodes[" + std::to_string(i) + "]";
    if (n.node().empty()) throw BadRequest(field + ".node", "name a node (SceneHandle.nodes lists them)");
    if (n.world_size() != 16) {
      throw BadRequest(field + ".world",
                       "expected 16 values (a 4x4 matrix, column-major), got " + std::to_string(n.world_size()));
    }
    NodeEdit edit{n.node(), glm::dmat4(1.0)};
    for (int k = 0; k < 16; ++k) edit.world[k / 4][k % 4] = n.world(k);  // finiteness: setNodeWorldMatrix
    edits.push_back(std::move(edit));
  }
  return edits;
}

std::optional<glm::dvec3> vec3If(bool present, const v1::Vec3& v) {
  if (!present) return std::nullopt;
  return glm::dvec3(v.x(), v.y(), v.z());
}

std::vector<std::pair<std::size_t, LightEdit>> readLightEdits(const v1::UpdateSceneRequest& request) {
  std::vector<std::pair<std::size_t, LightEdit>> edits;
  for (const v1::LightUpdate& l : request.lights()) {
    LightEdit edit;
    edit.position = vec3If(l.has_position(), l.position());
    edit.direction = vec3If(l.has_direction(), l.direction());
    edit.color = vec3If(l.has_color(), l.color());
    if (l.has_intensity()) edit.intensity = l.intensity();
    edits.emplace_back(l.index(), edit);
  }
  return edits;
}

}  // namespace

std::string clientKey(const grpc::ServerContext& context) {
  return context.peer() + "#" + std::to_string(reinterpret_cast<std::uintptr_t>(&context));
}

grpc::Status HolotraceService::ListDisplays(grpc::ServerContext*, const v1::ListDisplaysRequest*,
                                            v1::ListDisplaysResponse* response) {
  return guarded([&] {
    for (const auto& display : state_.displays.list()) fillDisplaySummary(*display, *response->add_displays());
    return grpc::Status::OK;
  });
}

grpc::Status HolotraceService::GetDisplay(grpc::ServerContext*, const v1::GetDisplayRequest* request,
                                          v1::Display* response) {
  return guarded([&] {
    fillDisplay(*state_.displays.find(request->display_id()), *response);
    return grpc::Status::OK;
  });
}

grpc::Status HolotraceService::LoadScene(grpc::ServerContext* context, const v1::LoadSceneRequest* request,
                                         v1::SceneHandle* response) {
  return guarded([&] {
    const std::string& given = request->path();
    if (given.rfind("builtin:", 0) == 0) {
      fillHandle(*state_.scenes.open(clientKey(*context), SceneSource{given, {}, {}, {}}), *response);
      return grpc::Status::OK;
    }
    resolveBeneath(state_.config.sceneRoot, "path", given);  // the name's rules; then one open beneath the root
    const SceneSource source =
        readSceneSourceBeneath(state_.config.sceneRoot, given, state_.config.limits.maxSceneBytes);
    fillHandle(*state_.scenes.open(clientKey(*context), source), *response);
    return grpc::Status::OK;
  });
}

grpc::Status HolotraceService::UploadScene(grpc::ServerContext* context,
                                           grpc::ServerReader<v1::UploadSceneChunk>* reader,
                                           v1::SceneHandle* response) {
  return guarded([&] {
    // Bounded before the first byte: a slot (limits.max_uploads), a stall timeout on every Read
    // (limits.upload_idle_seconds), the declared size against limits.max_upload_bytes_in_flight.
    UploadBudget::Slot slot(state_.uploads);
    CallWatchdog::Watch watch(state_.watchdog, *context, state_.config.limits.uploadIdleSeconds, "upload");
    const auto read = [&](v1::UploadSceneChunk& chunk) {
      const CallWatchdog::Watch::Wait waiting(watch);
      return reader->Read(&chunk);
    };
    v1::UploadSceneChunk chunk;
    if (!read(chunk) || !chunk.has_info()) {
      if (watch.stalled()) throw ClientGone("upload stalled (limits.upload_idle_seconds)");
      throw BadRequest("info", "the first message must carry info");
    }
    const std::string fileName = chunk.info().file_name();
    checkSceneExtension(fileName);
    const std::uint64_t total = chunk.info().total_bytes();
    if (total > state_.config.limits.maxSceneBytes) {
      throw LimitExceeded("upload of " + std::to_string(total) + " bytes (limits.max_scene_bytes = " +
                          std::to_string(state_.config.limits.maxSceneBytes) + ")");
    }
    slot.reserve(total);
    std::vector<std::uint8_t> bytes;
    bytes.reserve(total);
    while (read(chunk)) {
      if (!chunk.has_data()) throw BadRequest("data", "only the first message may carry info");
      if (bytes.size() + chunk.data().size() > total) throw BadRequest("data", "more bytes than info.total_bytes");
      bytes.insert(bytes.end(), chunk.data().begin(), chunk.data().end());
    }
    if (watch.stalled()) throw ClientGone("upload stalled (limits.upload_idle_seconds)");
    if (context->IsCancelled()) throw ClientGone("upload cancelled");
    if (bytes.size() != total) throw BadRequest("data", "fewer bytes than info.total_bytes");
    // Loaded from memory under the client's file name (an uploaded .gltf can only use data: URIs; a quilt's layout
    // comes from the name's _qs tag or the file's metadata, docs/SERVICE.md §12).
    const SceneSource source{fileName, std::string(bytes.begin(), bytes.end()), {}, {}};
    try {
      fillHandle(*state_.scenes.open(clientKey(*context), source), *response);
    } catch (const ConfigError& e) {  // a quilt without a usable layout: the name is the client's to fix
      throw BadRequest("info.file_name", e.what());
    }
    return grpc::Status::OK;
  });
}

grpc::Status HolotraceService::UpdateScene(grpc::ServerContext* context, const v1::UpdateSceneRequest* request,
                                           v1::UpdateSceneResponse* response) {
  return guarded([&] {
    CameraPlacement placement;
    if (request->has_target()) {
      const auto& t = request->target();
      if (!std::isfinite(t.x()) || !std::isfinite(t.y()) || !std::isfinite(t.z())) {
        throw BadRequest("target", "must be finite");
      }
      placement.target = glm::dvec3(t.x(), t.y(), t.z());
    }
    if (request->size() != 0.0) {
      if (!std::isfinite(request->size()) || request->size() < 0.0) throw BadRequest("size", "must be > 0");
      placement.size = request->size();
    }
    std::optional<double> observerDistance, observerHeight;
    if (request->has_observer_distance()) {
      if (!std::isfinite(request->observer_distance()) || request->observer_distance() <= 0.0) {
        throw BadRequest("observer_distance", "must be finite and > 0 (display units)");
      }
      observerDistance = request->observer_distance();
    }
    if (request->has_observer_height()) {
      if (!std::isfinite(request->observer_height())) throw BadRequest("observer_height", "must be finite");
      observerHeight = request->observer_height();
    }
    const bool cameraChange = placement.target || placement.size || observerDistance || observerHeight;
    const std::vector<NodeEdit> nodes = readNodeEdits(*request);
    const std::vector<std::pair<std::size_t, LightEdit>> lights = readLightEdits(*request);
    if (!cameraChange && nodes.empty() && lights.empty()) {
      throw BadRequest("target", "give a target, a size, an observer position, nodes and/or lights");
    }
    if (!nodes.empty() || !lights.empty()) {  // first: a refused edit leaves the camera as it was too
      const SceneLibrary::EditResult result =
          state_.scenes.editScene(clientKey(*context), request->scene_id(), !nodes.empty(), [&](Scene& scene) {
            for (const NodeEdit& n : nodes) setNodeWorldMatrix(scene, n.name, n.world);
            for (const auto& [index, edit] : lights) editLight(scene, index, edit);
          });
      response->set_rebuild_ms(result.updateMs);
      response->set_sah_cost(result.sahCost);
      response->set_bvh_layout(bvh::bvhLayoutName(result.bvh.layout));
      response->set_bvh_full_builds(result.bvh.fullBuilds);
      response->set_bvh_instance_updates(result.bvh.instanceUpdates);
    }
    if (!cameraChange) return grpc::Status::OK;
    // An observer-only update keeps the camera placement of earlier updates.
    if (!placement.target && !placement.size) placement = state_.scenes.find(request->scene_id())->cameraOverride;
    state_.scenes.updateCamera(request->scene_id(), placement, observerDistance, observerHeight);
    return grpc::Status::OK;
  });
}

grpc::Status HolotraceService::Status(grpc::ServerContext*, const v1::StatusRequest*, v1::StatusResponse* response) {
  return guarded([&] {
    const WorkerStats stats = state_.worker.stats();
    auto* device = response->add_devices();
    device->set_name(stats.deviceName);
    device->set_frames_rendered(stats.framesRendered);
    device->set_last_frame_ms(stats.lastFrameMs);
    device->set_mean_frame_ms(stats.meanFrameMs);
    device->set_queued(stats.queued);
    response->set_active_streams(state_.activeStreams.load());
    response->set_scenes_loaded(static_cast<std::uint32_t>(state_.scenes.contentCount()));
    response->set_version(HT_VERSION);
    const ProcessStats self = readProcessStats(::getpid());
    response->set_pid(static_cast<std::uint32_t>(::getpid()));
    response->set_resident_kib(self.residentKiB);
    response->set_cpu_seconds(self.cpuSeconds);
    response->set_threads(self.threads);
    addPanelStatuses(state_, *response);
    addClusterStatus(state_, *response);
    const SceneLibraryStats scenes = state_.scenes.stats();
    response->set_scene_sessions(scenes.sessions);
    response->set_scene_memory_bytes(scenes.memoryBytes);
    response->set_scene_sessions_released(scenes.sessionsReleased);
    response->set_open_fds(self.openFds);
    for (const StreamStatusEntry& entry : state_.progressive.status()) {
      v1::StreamStatus& stream = *response->add_streams();
      stream.set_scene_id(entry.sceneId);
      stream.set_display_id(entry.displayId);
      stream.set_state(entry.framesRendered == 0 ? v1::STREAM_STATE_UNSPECIFIED
                       : entry.report.converged  ? v1::STREAM_STATE_CONVERGED
                                                 : v1::STREAM_STATE_ACCUMULATING);
      stream.set_accumulated_spp(entry.report.minSamples);
      stream.set_accumulated_spp_max(entry.report.maxSamples);
      stream.set_error_estimate(entry.report.maxError);
      stream.set_clients(entry.clients);
      stream.set_frames_rendered(entry.framesRendered);
      stream.set_accumulator_bytes(entry.bytes);
    }
    response->set_accumulator_bytes(state_.progressive.bytesInUse());
    response->set_accumulator_limit_bytes(state_.progressive.limitBytes());
    return grpc::Status::OK;
  });
}

grpc::Status HolotraceService::UnloadScene(grpc::ServerContext*, const v1::UnloadSceneRequest* request,
                                           v1::UnloadSceneResponse*) {
  return guarded([&] {
    state_.scenes.unload(request->scene_id());
    return grpc::Status::OK;
  });
}

}  // namespace ht::server
