// scene_library.cpp - see scene_library.h.
#include "server/scene_library.h"

#include <chrono>
#include <cstdio>

#include "scene/load_scene.h"
#include "server/path_rules.h"

namespace ht::server {

std::string contentHash(std::span<const std::uint8_t> bytes) {
  std::uint64_t h = 1469598103934665603ull;  // FNV-1a 64 offset basis
  for (std::uint8_t b : bytes) {
    h ^= b;
    h *= 1099511628211ull;  // FNV prime
  }
  char text[17];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(h));
  return text;
}

SceneLibrary::SceneLibrary(RenderWorker& worker, std::uint64_t maxTriangles, std::size_t maxSessions)
    : worker_(worker), maxTriangles_(maxTriangles), maxSessions_(maxSessions) {}

SceneLibrary::~SceneLibrary() {
  sessions_.clear();
  contents_.clear();
}

std::shared_ptr<SceneContent> SceneLibrary::build(const std::string& client, const std::string& key,
                                                  const std::string& spec, std::span<const std::uint8_t> bytes) {
  auto content = std::make_shared<SceneContent>();
  content->contentKey = key;
  const auto start = std::chrono::steady_clock::now();
  if (isQuiltSpec(spec)) {  // a quilt image: shown by interleaving, nothing to trace
    content->quilt = std::make_shared<const QuiltContent>(std::filesystem::path(spec).filename().string(), bytes);
    content->loadMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    return content;
  }
  content->scene = loadScene(spec);
  content->loadMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  if (content->scene.triangleCount() > maxTriangles_) {
    throw LimitExceeded("scene has " + std::to_string(content->scene.triangleCount()) +
                        " triangles (limits.max_triangles = " + std::to_string(maxTriangles_) + ")");
  }
  worker_
      .submit(
          client,
          [&content](gpu::VulkanContext& context) {
            content->renderer = std::make_shared<gpu::Renderer>(context, content->scene);
          },
          false)
      .get();
  return content;
}

std::shared_ptr<const SceneSession> SceneLibrary::open(const std::string& client, const std::string& spec,
                                                       std::span<const std::uint8_t> bytes) {
  std::string key = bytes.empty() ? spec : contentHash(bytes) + spec.substr(spec.rfind('.') + 1);
  // A quilt's layout comes from its name as much as from its bytes (server/quilt_content.h).
  if (!bytes.empty() && isQuiltSpec(spec)) key += "\n" + std::filesystem::path(spec).filename().string();
  std::shared_ptr<SceneContent> content;
  bool reused = false;
  {
    std::lock_guard building(buildMutex_);
    {
      std::lock_guard lock(mutex_);
      if (sessions_.size() >= maxSessions_) throw LimitExceeded("too many scene sessions loaded");
      auto it = contents_.find(key);
      if (it != contents_.end()) content = it->second, reused = true;
    }
    if (!content) {
      content = build(client, key, spec, bytes);
      std::lock_guard lock(mutex_);
      contents_[key] = content;
    }
  }
  std::lock_guard lock(mutex_);
  auto session = std::make_shared<SceneSession>();
  session->id =
      "s" + std::to_string(nextSession_++) + "-" + (bytes.empty() ? std::string("builtin") : key.substr(0, 16));
  session->content = content;
  session->reused = reused;
  sessions_[session->id] = session;
  return session;
}

std::shared_ptr<const SceneSession> SceneLibrary::find(const std::string& id) const {
  std::lock_guard lock(mutex_);
  auto it = sessions_.find(id);
  if (it == sessions_.end()) throw UnknownScene("unknown scene_id '" + id + "' (LoadScene returns one)");
  return it->second;
}

void SceneLibrary::updateCamera(const std::string& id, const CameraPlacement& placement,
                                std::optional<double> observerDistance, std::optional<double> observerHeight) {
  std::lock_guard lock(mutex_);
  auto it = sessions_.find(id);
  if (it == sessions_.end()) throw UnknownScene("unknown scene_id '" + id + "' (LoadScene returns one)");
  auto updated = std::make_shared<SceneSession>(*it->second);  // sessions are immutable once published
  updated->cameraOverride = placement;
  if (observerDistance) updated->observerDistance = observerDistance;
  if (observerHeight) updated->observerHeight = observerHeight;
  it->second = std::move(updated);
}

SceneLibrary::EditResult SceneLibrary::editScene(const std::string& client, const std::string& id, bool movesGeometry,
                                                 const std::function<void(Scene&)>& edit) {
  std::lock_guard editing(buildMutex_);  // one BVH build at a time, and edits of one session in order
  const std::shared_ptr<const SceneSession> session = find(id);
  if (session->content->quilt) throw BadRequest("scene_id", "'" + id + "' is a quilt image: it has no nodes or lights");
  auto content = std::make_shared<SceneContent>(*session->content);  // copies the scene, shares the Renderer
  edit(content->scene);
  const bool newRenderer = content->editedBy != id;
  const auto start = std::chrono::steady_clock::now();
  worker_
      .submit(
          client,
          [&](gpu::VulkanContext& context) {
            if (newRenderer)
              content->renderer = std::make_shared<gpu::Renderer>(context, content->scene);
            else if (movesGeometry)
              content->renderer->replaceScene(content->scene);
            else
              content->renderer->updateLights(content->scene);
          },
          false)
      .get();
  EditResult result;
  result.updateMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  result.sahCost = content->renderer->bvhReport().sahCost;
  if (newRenderer) {
    content->editedBy = id;
    content->contentKey += "@" + id;
  }
  std::lock_guard lock(mutex_);
  auto it = sessions_.find(id);
  if (it == sessions_.end()) throw UnknownScene("unknown scene_id '" + id + "' (LoadScene returns one)");
  auto updated = std::make_shared<SceneSession>(*it->second);  // keeps camera updates made meanwhile
  updated->content = std::move(content);
  it->second = std::move(updated);
  return result;
}

std::size_t SceneLibrary::contentCount() const {
  std::lock_guard lock(mutex_);
  return contents_.size();
}

}  // namespace ht::server
