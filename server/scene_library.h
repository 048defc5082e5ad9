// scene_library.h - loaded scenes. Content (keyed by a hash of the file bytes, or the builtin name) is loaded and
// its BVH built and uploaded once; every LoadScene returns a new session handle with its own camera placement
// that shares that content (and its Renderer) with other sessions loading the same bytes.
//
// Nothing is kept for ever (docs/SERVICE.md §5 "Scene sessions and memory"): a session ends by UnloadScene, after
// `idleSeconds` without use, or as the least recently used idle session when `maxSessions` are open; contents are
// kept for reuse while their estimated memory (Scene + BVH + device buffers) fits `memoryBudget`, evicted least
// recently used first. Sessions that a running call pinned (StreamFrames, Capture) are never ended by either.
// Loads of different contents run concurrently; a second load of the same bytes waits for the first and reuses it.
#pragma once
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <future>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <span>
#include <string>

#include "camera_models/display_config.h"
#include "gpu/renderer.h"
#include "scene/scene.h"
#include "scene/scene_source.h"
#include "server/errors.h"
#include "server/quilt_content.h"
#include "server/render_worker.h"

namespace ht::server {

// Published contents are never modified: an edit makes a new SceneContent (EditResult below).
struct SceneContent {
  std::string contentKey;
  Scene scene;
  Bounds3 loadBounds;  // the scene's bounds when it was loaded: automatic camera placement stays there after edits
                       // (a moved node must not re-centre the whole view, docs/REUSE.md §6 item 9)
  std::shared_ptr<gpu::Renderer> renderer;  // used on the render worker thread only, and destroyed there
  double loadMs = 0.0;
  std::uint64_t memoryBytes = 0;  // estimate: sceneMemoryBytes(scene), or the decoded quilt image
  std::string editedBy;   // "" = loaded content, shared by every session of the same bytes; else the one session
                          // whose edits (UpdateScene nodes / lights) it carries
  bool twoLevel = false;  // the session's own renderer (editedBy != "") traces the two-level BVH
  std::shared_ptr<const QuiltContent> quilt;  // a quilt image (server/quilt_content.h): no scene, no renderer
};

struct SceneSession {
  std::string id;
  std::shared_ptr<SceneContent> content;
  CameraPlacement cameraOverride;                          // target / size set by UpdateScene (unset = display's own)
  std::optional<double> observerDistance, observerHeight;  // tracked HPO observer (UpdateScene)
  bool reused = false;
};

struct SceneLibraryLimits {
  std::uint64_t maxTriangles = 5'000'000;
  std::uint32_t maxSessions = 256;
  double idleSeconds = 600.0;
  std::uint64_t memoryBudget = 2ull << 30;
};

struct SceneLibraryStats {
  std::uint32_t sessions = 0;
  std::uint32_t contents = 0;     // distinct contents alive (cached, or held by a session)
  std::uint64_t memoryBytes = 0;  // their estimated memory
  std::uint64_t sessionsReleased = 0;
  std::uint64_t contentsEvicted = 0;
};

// What a scene costs in memory, host copy + device copy + BVH, estimated from its arrays: the budget's unit.
std::uint64_t sceneMemoryBytes(const Scene& scene);

class SceneLibrary {
 public:
  using Clock = std::chrono::steady_clock;

  SceneLibrary(RenderWorker& worker, SceneLibraryLimits limits);
  ~SceneLibrary();  // releases the Renderers; call after the worker stopped, before the Vulkan context dies

  // `source` holds every byte the scene is loaded from (scene/scene_source.h; read once beneath the scene root, or
  // uploaded), or only a name "builtin:NAME". Contents are shared by a key over all those bytes. `client` is
  // charged for the BVH upload job. Throws LimitExceeded when every session is pinned or the content does not fit
  // the memory budget beside the pinned ones.
  std::shared_ptr<const SceneSession> open(const std::string& client, const SceneSource& source);
  std::shared_ptr<const SceneSession> find(const std::string& id);  // counts as use; throws UnknownScene
  void unload(const std::string& id);                               // throws UnknownScene

  // Keeps a session from idling out or being evicted while a call renders it (and counts as use at both ends).
  class Pin {
   public:
    Pin(SceneLibrary& library, std::string id);  // throws UnknownScene
    ~Pin();
    Pin(const Pin&) = delete;
    Pin& operator=(const Pin&) = delete;

   private:
    SceneLibrary& library_;
    std::string id_;
  };

  // Replaces the camera override; observer values replace the tracked observer where given.
  void updateCamera(const std::string& id, const CameraPlacement& placement,
                    std::optional<double> observerDistance = std::nullopt,
                    std::optional<double> observerHeight = std::nullopt);
  // Applies `edit` to a copy of the session's scene, updates the device copy on the render worker (charged to
  // `client`) and publishes a session with the edited content; other sessions of the same bytes keep theirs. The
  // first edit of a session gives it its own Renderer (pipelines are the device's, gpu/pipeline_library.h: nothing
  // recompiles); later ones reuse it: Renderer::moveNodes (on the two-level BVH a first edit that moves nodes
  // builds: a refit + top-level update, no rebuild) when `movesGeometry`, else only the lights are re-uploaded
  // (Renderer::updateLights). `edit` throws (SceneError) to refuse; nothing changes then.
  struct EditResult {
    double updateMs = 0.0;  // the device update: Renderer, BVH rebuild or light upload
    double sahCost = 0.0;
    gpu::BvhStats bvh;  // the session renderer's BVH layout and build/update counts after the edit
  };
  EditResult editScene(const std::string& client, const std::string& id, bool movesGeometry,
                       const std::function<void(Scene&)>& edit);
  // Gives session `id` its own Renderer now, as its first edit would (nothing for a quilt or a session that has one):
  // a session whose frames keep reuse state (RenderRequest.reuse_after_edits) needs it before the frame that records
  // the state, or its first edit would start a new Renderer without it. The copy counts against the scene budget.
  // forNodeMoves: the Renderer traces the two-level BVH, whose progressive accumulations record the segment cells a
  // node move's partial restart needs (a progressive stream with reuse_after_edits; docs/REUSE.md §7): a session
  // whose own Renderer traces the flattened BVH gets a new one on the two-level BVH (its reuse state and
  // accumulations start over once).
  // Returns the session as it is now, for the caller's frame job.
  std::shared_ptr<const SceneSession> ownRenderer(const std::string& client, const std::string& id,
                                                  bool forNodeMoves = false);

  // Ends sessions idle for longer than the TTL and evicts contents over the budget (the daemon calls it
  // periodically; every open() does too). True if any session or content was released since the last sweep.
  bool sweep();
  std::size_t contentCount() const;
  SceneLibraryStats stats() const;

 private:
  struct SessionEntry {
    std::shared_ptr<const SceneSession> session;
    Clock::time_point lastUsed;
    std::uint32_t pins = 0;
  };
  struct CachedContent {
    std::shared_ptr<SceneContent> content;
    Clock::time_point lastUsed;
  };
  using Building = std::shared_future<std::shared_ptr<SceneContent>>;

  std::shared_ptr<SceneContent> build(const std::string& client, const std::string& key, const SceneSource& source);
  void checkMemoryBudget(std::uint64_t bytes) const;  // LimitExceeded over limits.max_scene_memory_bytes
  std::shared_ptr<SceneContent> contentFor(const std::string& client, const std::string& key, const SceneSource& source,
                                           bool& reused);
  std::shared_ptr<gpu::Renderer> adopt(gpu::Renderer* renderer);  // owned, destroyed on the render worker
  SessionEntry& entryLocked(const std::string& id);               // throws UnknownScene
  void expireLocked(Clock::time_point now);
  bool evictOneSessionLocked(const std::string& keep);
  // Evicts unreferenced cached contents LRU, then (evictSessions) idle sessions LRU, until the budget holds; throws
  // LimitExceeded if pinned sessions alone exceed it (evictSessions), else returns.
  void fitBudgetLocked(const std::string& keepSession, bool evictSessions);
  std::uint64_t memoryLocked() const;
  std::map<const SceneContent*, std::uint64_t> liveContentsLocked() const;

  RenderWorker& worker_;
  const SceneLibraryLimits limits_;
  mutable std::mutex mutex_;
  std::mutex editMutex_;  // edits of one session in order, one edit BVH build at a time
  std::map<std::string, CachedContent> contents_;
  std::map<std::string, Building> building_;  // loads in progress, by content key
  std::map<std::string, SessionEntry> sessions_;
  std::uint64_t nextSession_ = 1;
  std::uint64_t sessionsReleased_ = 0, contentsEvicted_ = 0;
  std::uint64_t releasedAtLastSweep_ = 0;
};

// 64-bit FNV-1a of `bytes`, as 16 hex digits (content key; not a security boundary).
std::string contentHash(std::span<const std::uint8_t> bytes);
// The content key of a source: the builtin name, or hashes of the main file and of every external file with its
// URI, plus the extension; two sources share a key only when every byte loaded is the same.
std::string sourceKey(const SceneSource& source);

}  // namespace ht::server
