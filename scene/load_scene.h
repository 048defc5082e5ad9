// load_scene.h - loadScene() with a load report (the plain loadScene(spec) is declared in scene.h).
#pragma once
#include <string>

#include "scene/load_report.h"
#include "scene/scene.h"
#include "scene/scene_source.h"

namespace ht {

// Dispatches on "builtin:NAME" or the file extension (.gltf .glb .obj .off, case-insensitive) and fills
// `report`. Throws SceneError naming the spec when the scheme or extension is not supported.
Scene loadScene(const std::string& spec, SceneLoadReport& report);

// Loads from bytes read beforehand (scene_source.h), dispatching on the extension of `source.name`.
// `limits` (scene_limits.h) are checked from the file's headers before allocating.
Scene loadScene(const SceneSource& source, SceneLoadReport& report, const SceneLimits& limits = {});
Scene loadScene(const SceneSource& source, const SceneLimits& limits = {});

}  // namespace ht
