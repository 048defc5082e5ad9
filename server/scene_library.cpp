// scene_library.cpp - see scene_library.h.
#include "server/scene_library.h"

#include <chrono>
#include <cstdio>

#include "bvh/gpu_layout.h"
#include "frame_io/quilt_file.h"
#include "scene/load_scene.h"
#include "scene/scene_edits.h"
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

std::uint64_t sceneMemoryBytes(const Scene& scene) {
  std::uint64_t texels = 0;
  for (const Texture& t : scene.textures) texels += t.texels.size();
  const std::uint64_t vertices = scene.positions.size(), normals = scene.normals.size(), uvs = scene.texcoords.size(),
                      triangles = scene.triangles.size();
  const std::uint64_t host = vertices * 12 + normals * 12 + uvs * 8 + triangles * 16 + texels * 16 +
                             scene.materials.size() * sizeof(Material) + scene.lights.size() * sizeof(Light);
  // Device: vec4 vertices and normals, vec2 uvs, uvec4 triangles, texels; BVH: <= 2 nodes of 64 bytes per triangle
  // plus a 48-byte triangle record (gpu/gpu_scene.h, bvh/gpu_layout.h).
  const std::uint64_t device =
      vertices * 16 + normals * 16 + uvs * 8 + triangles * 16 + texels * 16 + triangles * (2 * 64 + 48);
  return host + device;
}

namespace {

std::span<const std::uint8_t> asBytes(const std::string& text) {
  return {reinterpret_cast<const std::uint8_t*>(text.data()), text.size()};
}

}  // namespace

std::string sourceKey(const SceneSource& source) {
  if (source.bytes.empty() && source.name.rfind("builtin:", 0) == 0) return source.name;
  std::string key = contentHash(asBytes(source.bytes)) + source.name.substr(source.name.rfind('.') + 1);
  for (const auto& [uri, bytes] : source.externals)
    key += "+" + contentHash(asBytes(uri)) + contentHash(asBytes(bytes));
  return key;
}

SceneLibrary::SceneLibrary(RenderWorker& worker, SceneLibraryLimits limits) : worker_(worker), limits_(limits) {}

SceneLibrary::~SceneLibrary() {
  sessions_.clear();
  contents_.clear();
}

std::shared_ptr<gpu::Renderer> SceneLibrary::adopt(gpu::Renderer* renderer) {
  // A Renderer frees command buffers of the device's shared pool: it must die on the render worker thread, wherever
  // its last owner lets go (an evicted session, a frame job that held it).
  return std::shared_ptr<gpu::Renderer>(renderer,
                                        [&worker = worker_](gpu::Renderer* r) { worker.dispose([r] { delete r; }); });
}

void SceneLibrary::checkMemoryBudget(std::uint64_t bytes) const {
  if (bytes > limits_.memoryBudget) {
    throw LimitExceeded("scene needs about " + std::to_string(bytes >> 20) + " MiB (limits.max_scene_memory_bytes = " +
                        std::to_string(limits_.memoryBudget >> 20) + " MiB)");
  }
}

std::shared_ptr<SceneContent> SceneLibrary::build(const std::string& client, const std::string& key,
                                                  const SceneSource& source) {
  auto content = std::make_shared<SceneContent>();
  content->contentKey = key;
  const auto start = std::chrono::steady_clock::now();
  if (frame_io::isQuiltImageFile(source.name)) {  // a quilt image: shown by interleaving, nothing to trace
    content->quilt = std::make_shared<const QuiltContent>(std::filesystem::path(source.name).filename().string(),
                                                          asBytes(source.bytes));
    content->loadMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    content->memoryBytes = content->quilt->memoryBytes();
    checkMemoryBudget(content->memoryBytes);
    return content;
  }
  SceneLimits limits;  // counts refused from the file's headers, before the memory is allocated
  limits.maxTriangles = limits_.maxTriangles;
  limits.maxVertices = 3 * limits_.maxTriangles;
  content->scene = source.name.rfind("builtin:", 0) == 0 ? loadScene(source.name) : loadScene(source, limits);
  content->loadBounds = content->scene.bounds();
  content->loadMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  if (content->scene.triangleCount() > limits_.maxTriangles) {
    throw LimitExceeded("scene has " + std::to_string(content->scene.triangleCount()) +
                        " triangles (limits.max_triangles = " + std::to_string(limits_.maxTriangles) + ")");
  }
  content->memoryBytes = sceneMemoryBytes(content->scene);
  checkMemoryBudget(content->memoryBytes);
  // The BVH is built here, on the loading call's thread: the render worker only uploads it, so other clients'
  // frames wait for an upload, not for a build (loads never block other clients' frames, docs/SERVICE.md §5).
  // The layout (flattened or two-level) is chosen per scene, measured (docs/BVH.md §9.4).
  gpu::SceneBvh bvh = gpu::buildSceneBvh(content->scene, {}, gpu::BvhLayoutPolicy::Automatic);
  worker_
      .submit(
          client,
          [&](gpu::VulkanContext& context) {
            content->renderer = adopt(new gpu::Renderer(context, content->scene, std::move(bvh)));
          },
          false)
      .get();
  return content;
}

std::shared_ptr<SceneContent> SceneLibrary::contentFor(const std::string& client, const std::string& key,
                                                       const SceneSource& source, bool& reused) {
  std::unique_lock lock(mutex_);
  if (auto cached = contents_.find(key); cached != contents_.end()) {
    cached->second.lastUsed = Clock::now();
    reused = true;
    return cached->second.content;
  }
  if (auto inProgress = building_.find(key); inProgress != building_.end()) {
    Building pending = inProgress->second;  // the same bytes are being loaded: wait for that load and share it
    lock.unlock();
    reused = true;
    return pending.get();
  }
  std::promise<std::shared_ptr<SceneContent>> promise;
  building_[key] = promise.get_future().share();
  lock.unlock();  // other contents load meanwhile
  std::shared_ptr<SceneContent> content;
  try {
    content = build(client, key, source);
  } catch (...) {
    lock.lock();
    building_.erase(key);
    promise.set_exception(std::current_exception());
    throw;
  }
  lock.lock();
  contents_[key] = CachedContent{content, Clock::now()};
  building_.erase(key);
  promise.set_value(content);
  return content;
}

std::shared_ptr<const SceneSession> SceneLibrary::open(const std::string& client, const SceneSource& source) {
  std::string key = sourceKey(source);
  const bool builtin = key == source.name;
  // A quilt's layout comes from its name as much as from its bytes (server/quilt_content.h).
  if (!builtin && frame_io::isQuiltImageFile(source.name))
    key += "\n" + std::filesystem::path(source.name).filename().string();
  bool reused = false;
  std::shared_ptr<SceneContent> content = contentFor(client, key, source, reused);
  std::lock_guard lock(mutex_);
  expireLocked(Clock::now());
  while (sessions_.size() >= limits_.maxSessions) {
    if (!evictOneSessionLocked("")) {
      throw LimitExceeded("all " + std::to_string(limits_.maxSessions) +
                          " scene sessions are being rendered (limits.max_scene_sessions)");
    }
  }
  auto session = std::make_shared<SceneSession>();
  session->id = "s" + std::to_string(nextSession_++) + "-" + (builtin ? std::string("builtin") : key.substr(0, 16));
  session->content = content;
  session->reused = reused;
  sessions_[session->id] = SessionEntry{session, Clock::now(), 0};
  try {
    fitBudgetLocked(session->id, true);
  } catch (const LimitExceeded&) {
    sessions_.erase(session->id);
    fitBudgetLocked("", false);  // the refused content leaves the cache again
    throw;
  }
  return session;
}

SceneLibrary::SessionEntry& SceneLibrary::entryLocked(const std::string& id) {
  auto it = sessions_.find(id);
  const auto now = Clock::now();
  if (it != sessions_.end() && it->second.pins == 0 &&
      std::chrono::duration<double>(now - it->second.lastUsed).count() > limits_.idleSeconds) {
    sessions_.erase(it);  // idled out; the periodic sweep had not come round yet
    ++sessionsReleased_;
    it = sessions_.end();
  }
  if (it == sessions_.end()) {
    throw UnknownScene("unknown scene_id '" + id +
                       "' (LoadScene returns one; a session ends by UnloadScene, after limits.scene_idle_seconds "
                       "without use, or when limits.max_scene_sessions / max_scene_memory_bytes need its room)");
  }
  it->second.lastUsed = now;
  return it->second;
}

std::shared_ptr<const SceneSession> SceneLibrary::find(const std::string& id) {
  std::lock_guard lock(mutex_);
  return entryLocked(id).session;
}

void SceneLibrary::unload(const std::string& id) {
  std::lock_guard lock(mutex_);
  entryLocked(id);
  sessions_.erase(id);
  ++sessionsReleased_;
}

SceneLibrary::Pin::Pin(SceneLibrary& library, std::string id) : library_(library), id_(std::move(id)) {
  std::lock_guard lock(library_.mutex_);
  ++library_.entryLocked(id_).pins;
}

SceneLibrary::Pin::~Pin() {
  std::lock_guard lock(library_.mutex_);
  auto it = library_.sessions_.find(id_);  // gone if unloaded meanwhile
  if (it == library_.sessions_.end()) return;
  --it->second.pins;
  it->second.lastUsed = Clock::now();
}

void SceneLibrary::expireLocked(Clock::time_point now) {
  const auto idle = [&](Clock::time_point last) {
    return std::chrono::duration<double>(now - last).count() > limits_.idleSeconds;
  };
  for (auto it = sessions_.begin(); it != sessions_.end();) {
    if (it->second.pins == 0 && idle(it->second.lastUsed)) {
      it = sessions_.erase(it);
      ++sessionsReleased_;
    } else {
      ++it;
    }
  }
  for (auto it = contents_.begin(); it != contents_.end();) {
    bool referenced = false;
    for (const auto& [id, entry] : sessions_) referenced = referenced || entry.session->content == it->second.content;
    if (!referenced && idle(it->second.lastUsed)) {
      it = contents_.erase(it);
      ++contentsEvicted_;
    } else {
      ++it;
    }
  }
}

bool SceneLibrary::evictOneSessionLocked(const std::string& keep) {
  auto oldest = sessions_.end();
  for (auto it = sessions_.begin(); it != sessions_.end(); ++it) {
    if (it->second.pins != 0 || it->first == keep) continue;
    if (oldest == sessions_.end() || it->second.lastUsed < oldest->second.lastUsed) oldest = it;
  }
  if (oldest == sessions_.end()) return false;
  if (auto cached = contents_.find(oldest->second.session->content->contentKey); cached != contents_.end()) {
    cached->second.lastUsed = std::max(cached->second.lastUsed, oldest->second.lastUsed);
  }
  sessions_.erase(oldest);
  ++sessionsReleased_;
  return true;
}

std::map<const SceneContent*, std::uint64_t> SceneLibrary::liveContentsLocked() const {
  std::map<const SceneContent*, std::uint64_t> live;
  for (const auto& [key, cached] : contents_) live[cached.content.get()] = cached.content->memoryBytes;
  for (const auto& [id, entry] : sessions_) live[entry.session->content.get()] = entry.session->content->memoryBytes;
  return live;
}

std::uint64_t SceneLibrary::memoryLocked() const {
  std::uint64_t total = 0;
  for (const auto& [content, bytes] : liveContentsLocked()) total += bytes;
  return total;
}

void SceneLibrary::fitBudgetLocked(const std::string& keepSession, bool evictSessions) {
  while (memoryLocked() > limits_.memoryBudget) {
    auto oldest = contents_.end();  // least recently used cached content that no session holds
    for (auto it = contents_.begin(); it != contents_.end(); ++it) {
      bool referenced = false;
      for (const auto& [id, entry] : sessions_) referenced = referenced || entry.session->content == it->second.content;
      if (!referenced && (oldest == contents_.end() || it->second.lastUsed < oldest->second.lastUsed)) oldest = it;
    }
    if (oldest != contents_.end()) {
      contents_.erase(oldest);
      ++contentsEvicted_;
      continue;
    }
    if (evictSessions && evictOneSessionLocked(keepSession)) continue;
    if (!evictSessions) return;
    throw LimitExceeded("scene memory budget: about " + std::to_string(memoryLocked() >> 20) +
                        " MiB held by scenes being rendered (limits.max_scene_memory_bytes = " +
                        std::to_string(limits_.memoryBudget >> 20) + " MiB)");
  }
}

bool SceneLibrary::sweep() {
  std::lock_guard lock(mutex_);
  expireLocked(Clock::now());
  try {
    fitBudgetLocked("", true);
  } catch (const LimitExceeded&) {
    // Pinned sessions alone exceed the budget; loads are refused until their calls end.
  }
  const std::uint64_t released = sessionsReleased_ + contentsEvicted_;
  const bool any = released != releasedAtLastSweep_;
  releasedAtLastSweep_ = released;
  return any;
}

void SceneLibrary::updateCamera(const std::string& id, const CameraPlacement& placement,
                                std::optional<double> observerDistance, std::optional<double> observerHeight) {
  std::lock_guard lock(mutex_);
  SessionEntry& entry = entryLocked(id);
  auto updated = std::make_shared<SceneSession>(*entry.session);  // sessions are immutable once published
  updated->cameraOverride = placement;
  if (observerDistance) updated->observerDistance = observerDistance;
  if (observerHeight) updated->observerHeight = observerHeight;
  entry.session = std::move(updated);
}

namespace {

// Indices of the nodes whose world matrix an edit changed.
std::vector<std::uint32_t> movedNodes(const Scene& before, const Scene& after) {
  std::vector<std::uint32_t> moved;
  for (std::size_t n = 0; n < after.nodes.size() && n < before.nodes.size(); ++n)
    if (after.nodes[n].world != before.nodes[n].world) moved.push_back(static_cast<std::uint32_t>(n));
  return moved;
}

// Where the moved nodes' geometry was and is: what a frame that reuses the previous one re-traces around
// (gpu::Renderer::moveNodes, docs/REUSE.md §4); with one moved node, the balls around it too.
gpu::MovedBounds movedBounds(const Scene& before, const Scene& after, const std::vector<std::uint32_t>& moved) {
  gpu::MovedBounds bounds;
  for (const std::uint32_t n : moved) {
    for (const auto& [scene, into] : {std::pair{&before, &bounds.before}, std::pair{&after, &bounds.after}}) {
      const Bounds3 b = nodeWorldBounds(*scene, n);
      if (b.empty()) continue;
      into->extend(b.lo);
      into->extend(b.hi);
    }
  }
  if (moved.size() == 1) {
    bounds.beforeBall = nodeWorldBall(before, moved[0]);
    bounds.afterBall = nodeWorldBall(after, moved[0]);
  }
  return bounds;
}

}  // namespace

std::shared_ptr<const SceneSession> SceneLibrary::ownRenderer(const std::string& client, const std::string& id,
                                                              bool forNodeMoves) {
  const std::shared_ptr<const SceneSession> session = find(id);
  const SceneContent& content = *session->content;
  if (content.quilt) return session;
  if (content.editedBy == id && (content.twoLevel || !forNodeMoves)) return session;
  editScene(client, id, forNodeMoves, {});  // re-checked under the edit lock; forNodeMoves: the two-level BVH
  return find(id);
}

SceneLibrary::EditResult SceneLibrary::editScene(const std::string& client, const std::string& id, bool movesGeometry,
                                                 const std::function<void(Scene&)>& edit) {
  std::lock_guard editing(editMutex_);  // one edit BVH build at a time, and edits of one session in order
  const std::shared_ptr<const SceneSession> session = find(id);
  if (session->content->quilt) throw BadRequest("scene_id", "'" + id + "' is a quilt image: it has no nodes or lights");
  auto content = std::make_shared<SceneContent>(*session->content);  // copies the scene, shares the Renderer
  if (edit) edit(content->scene);
  const std::vector<std::uint32_t> moved = movedNodes(session->content->scene, content->scene);
  const bool ownedAlready = content->editedBy == id;
  // ownRenderer for node moves on a session whose own Renderer traces the flattened BVH: a new one, two-level.
  const bool relayout = !edit && movesGeometry && ownedAlready && !content->twoLevel;
  const bool newRenderer = !ownedAlready || relayout;
  if (!edit && !newRenderer) return {};  // ownRenderer: the session has its own already
  const auto start = std::chrono::steady_clock::now();
  // A first edit's BVH is built here, off the render worker (as a load's); a scene whose nodes move is traced with
  // the two-level BVH, so that later moves are a refit + top-level update, not a rebuild (docs/REUSE.md §3).
  gpu::SceneBvh bvh;
  if (newRenderer) {
    bvh = gpu::buildSceneBvh(content->scene, {},
                             movesGeometry ? gpu::BvhLayoutPolicy::TwoLevel : gpu::BvhLayoutPolicy::Automatic);
  }
  worker_
      .submit(
          client,
          [&](gpu::VulkanContext& context) {
            if (newRenderer)
              content->renderer = adopt(new gpu::Renderer(context, content->scene, std::move(bvh)));
            else if (movesGeometry)
              content->renderer->moveNodes(content->scene, moved,
                                           movedBounds(session->content->scene, content->scene, moved));
            else
              content->renderer->updateLights(content->scene);
          },
          false)
      .get();
  EditResult result;
  result.updateMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  result.sahCost = content->renderer->bvhReport().sahCost;
  result.bvh = content->renderer->bvhStats();
  content->twoLevel = result.bvh.layout == bvh::BvhLayout::TwoLevel;
  if (newRenderer && !ownedAlready) {
    content->editedBy = id;
    content->contentKey += "@" + id;
  }
  if (newRenderer) content->memoryBytes = sceneMemoryBytes(content->scene);
  std::lock_guard lock(mutex_);
  SessionEntry& entry = entryLocked(id);
  auto updated = std::make_shared<SceneSession>(*entry.session);  // keeps camera updates made meanwhile
  updated->content = std::move(content);
  entry.session = std::move(updated);
  try {
    fitBudgetLocked(id, true);
  } catch (const LimitExceeded&) {
    // Over budget until pinned calls end; the edit stands, later loads are refused meanwhile.
  }
  return result;
}

std::size_t SceneLibrary::contentCount() const {
  std::lock_guard lock(mutex_);
  return liveContentsLocked().size();
}

SceneLibraryStats SceneLibrary::stats() const {
  std::lock_guard lock(mutex_);
  SceneLibraryStats s;
  s.sessions = static_cast<std::uint32_t>(sessions_.size());
  const auto live = liveContentsLocked();
  s.contents = static_cast<std::uint32_t>(live.size());
  for (const auto& [content, bytes] : live) s.memoryBytes += bytes;
  s.sessionsReleased = sessionsReleased_;
  s.contentsEvicted = contentsEvicted_;
  return s;
}

}  // namespace ht::server
