// scene_rpcs.cpp - ListDisplays, GetDisplay, LoadScene, UploadScene, UpdateScene, Status.
#include <unistd.h>

#include <cmath>
#include <fstream>
#include <iterator>

#include "scene/scene_edits.h"
#include "server/display_messages.h"
#include "server/holotrace_service.h"
#include "server/path_rules.h"
#include "server/process_stats.h"
#include "server/status_mapping.h"

namespace ht::server {
namespace v1 = holotrace::v1;
namespace {

std::vector<std::uint8_t> readCapped(const std::filesystem::path& file, std::uint64_t maxBytes) {
  std::error_code ec;
  const auto size = std::filesystem::file_size(file, ec);
  if (ec) throw BadRequest("path", "cannot read '" + file.filename().string() + "': " + ec.message());
  if (size > maxBytes) {
    throw LimitExceeded("scene file is " + std::to_string(size) +
                        " bytes (limits.max_scene_bytes = " + std::to_string(maxBytes) + ")");
  }
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Symlinks inside the scene root must not lead out of it.
void checkStaysBeneath(const std::filesystem::path& root, const std::filesystem::path& file, const std::string& given) {
  std::error_code ec;
  const auto realRoot = std::filesystem::canonical(root, ec);
  const auto realFile = std::filesystem::canonical(file, ec);
  if (ec) throw BadRequest("path", "'" + given + "' does not exist below the scene root");
  const auto rel = realFile.lexically_relative(realRoot);
  if (rel.empty() || *rel.begin() == "..") throw AccessDenied("path '" + given + "' resolves outside the scene root");
}

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

std::string sceneExtension(const std::string& fileName) {
  checkFileNameComponent("info.file_name", fileName);
  const auto dot = fileName.rfind('.');
  const std::string ext = dot == std::string::npos ? "" : fileName.substr(dot);
  if (ext != ".glb" && ext != ".gltf" && ext != ".obj" && ext != ".off") {
    throw BadRequest("info.file_name", "'" + fileName + "' must end in .glb, .gltf, .obj or .off");
  }
  return ext;
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
      fillHandle(*state_.scenes.open(clientKey(*context), given, {}), *response);
      return grpc::Status::OK;
    }
    const auto file = resolveBeneath(state_.config.sceneRoot, "path", given);
    checkStaysBeneath(state_.config.sceneRoot, file, given);
    const auto bytes = readCapped(file, state_.config.limits.maxSceneBytes);
    fillHandle(*state_.scenes.open(clientKey(*context), file.string(), bytes), *response);
    return grpc::Status::OK;
  });
}

grpc::Status HolotraceService::UploadScene(grpc::ServerContext* context,
                                           grpc::ServerReader<v1::UploadSceneChunk>* reader,
                                           v1::SceneHandle* response) {
  return guarded([&] {
    v1::UploadSceneChunk chunk;
    if (!reader->Read(&chunk) || !chunk.has_info()) throw BadRequest("info", "the first message must carry info");
    const std::string ext = sceneExtension(chunk.info().file_name());
    const std::uint64_t total = chunk.info().total_bytes();
    if (total > state_.config.limits.maxSceneBytes) {
      throw LimitExceeded("upload of " + std::to_string(total) + " bytes (limits.max_scene_bytes = " +
                          std::to_string(state_.config.limits.maxSceneBytes) + ")");
    }
    std::vector<std::uint8_t> bytes;
    bytes.reserve(total);
    while (reader->Read(&chunk)) {
      if (!chunk.has_data()) throw BadRequest("data", "only the first message may carry info");
      if (bytes.size() + chunk.data().size() > total) throw BadRequest("data", "more bytes than info.total_bytes");
      bytes.insert(bytes.end(), chunk.data().begin(), chunk.data().end());
    }
    if (context->IsCancelled()) throw ClientGone("upload cancelled");
    if (bytes.size() != total) throw BadRequest("data", "fewer bytes than info.total_bytes");
    // The loaders read files: the bytes go to a private file named by their hash (docs/SERVICE.md §6).
    const std::string name = "upload-" + contentHash(bytes) + ext;
    state_.uploadSink.writeFile(name, bytes);
    const auto path = state_.config.workDir / name;
    struct Remove {
      std::filesystem::path p;
      ~Remove() {
        std::error_code ec;
        std::filesystem::remove(p, ec);
      }
    } remove{path};
    fillHandle(*state_.scenes.open(clientKey(*context), path.string(), bytes), *response);
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
    return grpc::Status::OK;
  });
}

}  // namespace ht::server
