// load_scene.h - loadScene() with a load report (the plain loadScene(spec) is declared in scene.h).
#pragma once
#include <string>

#include "scene/load_report.h"
#include "scene/scene.h"

namespace ht {

// Dispatches on "builtin:NAME" or the file extension (.gltf .glb .obj .off, case-insensitive) and fills
// `report`. Throws SceneError naming the spec when the scheme or extension is not supported.
Scene loadScene(const std::string& spec, SceneLoadReport& report);

}  // namespace ht
