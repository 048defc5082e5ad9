// scene_library.h - loaded scenes. Content (keyed by a hash of the file bytes, or the builtin name) is loaded and
// its BVH built and uploaded once; every LoadScene returns a new session handle with its own camera placement
// that shares that content (and its Renderer) with other sessions loading the same bytes.
#pragma once
#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <span>
#include <string>

#include "camera_models/display_config.h"
#include "gpu/renderer.h"
#include "scene/scene.h"
#include "server/errors.h"
#include "server/quilt_content.h"
#include "server/render_worker.h"

namespace ht::server {

// Published contents are never modified: an edit makes a new SceneContent (EditResult below).
struct SceneContent {
  std::string contentKey;
  Scene scene;
  std::shared_ptr<gpu::Renderer> renderer;  // used on the render worker thread only
  double loadMs = 0.0;
  std::string editedBy;  // "" = loaded content, shared by every session of the same bytes; else the one session
                         // whose edits (UpdateScene nodes / lights) it carries
  std::shared_ptr<const QuiltContent> quilt;  // a quilt image (server/quilt_content.h): no scene, no renderer
};

struct SceneSession {
  std::string id;
  std::shared_ptr<SceneContent> content;
  CameraPlacement cameraOverride;                          // target / size set by UpdateScene (unset = display's own)
  std::optional<double> observerDistance, observerHeight;  // tracked HPO observer (UpdateScene)
  bool reused = false;
};

class SceneLibrary {
 public:
  SceneLibrary(RenderWorker& worker, std::uint64_t maxTriangles, std::size_t maxSessions = 256);
  ~SceneLibrary();  // releases the Renderers; call after the worker stopped, before the Vulkan context dies

  // `spec` is a file path (already confined by the caller) or "builtin:NAME"; `bytes` are its contents (empty
  // for builtins). `client` is charged for the BVH upload job.
  std::shared_ptr<const SceneSession> open(const std::string& client, const std::string& spec,
                                           std::span<const std::uint8_t> bytes);
  std::shared_ptr<const SceneSession> find(const std::string& id) const;  // throws UnknownScene
  // Replaces the camera override; observer values replace the tracked observer where given.
  void updateCamera(const std::string& id, const CameraPlacement& placement,
                    std::optional<double> observerDistance = std::nullopt,
                    std::optional<double> observerHeight = std::nullopt);
  // Applies `edit` to a copy of the session's scene, updates the device copy on the render worker (charged to
  // `client`) and publishes a session with the edited content; other sessions of the same bytes keep theirs. The
  // first edit of a session gives it its own Renderer (pipelines are the device's, gpu/pipeline_library.h: nothing
  // recompiles); later ones reuse it: Renderer::replaceScene (new BVH) when `movesGeometry`, else only the lights are
  // re-uploaded (Renderer::updateLights). `edit` throws (SceneError) to refuse; nothing changes then.
  struct EditResult {
    double updateMs = 0.0;  // the device update: Renderer, BVH rebuild or light upload
    double sahCost = 0.0;
  };
  EditResult editScene(const std::string& client, const std::string& id, bool movesGeometry,
                       const std::function<void(Scene&)>& edit);
  std::size_t contentCount() const;

 private:
  std::shared_ptr<SceneContent> build(const std::string& client, const std::string& key, const std::string& spec,
                                      std::span<const std::uint8_t> bytes);

  RenderWorker& worker_;
  const std::uint64_t maxTriangles_;
  const std::size_t maxSessions_;
  mutable std::mutex mutex_;
  std::mutex buildMutex_;  // one content build at a time: a second load of the same bytes waits and reuses
  std::map<std::string, std::shared_ptr<SceneContent>> contents_;
  std::map<std::string, std::shared_ptr<const SceneSession>> sessions_;
  std::uint64_t nextSession_ = 1;
};

// 64-bit FNV-1a of `bytes`, as 16 hex digits (content key; not a security boundary).
std::string contentHash(std::span<const std::uint8_t> bytes);

}  // namespace ht::server
