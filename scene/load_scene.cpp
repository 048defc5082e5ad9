// load_scene.cpp - loadScene(): picks the loader from "builtin:" or the file extension.
#include "scene/load_scene.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <string_view>

#include "common/error.h"
#include "scene/builtin_scenes.h"
#include "scene/gltf_loader.h"
#include "scene/mesh_loader.h"

namespace ht {
namespace {

constexpr std::string_view kBuiltinPrefix = "builtin:";

std::string lowercaseExtension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

void summarize(const Scene& scene, SceneLoadReport& report) {
  report.triangles = scene.triangles.size();
  report.vertices = scene.positions.size();
  report.textures = scene.textures.size();
  report.lights = scene.lights.size();
}

}  // namespace

Scene loadScene(const std::string& spec, SceneLoadReport& report) {
  report = SceneLoadReport{};
  if (spec.rfind(kBuiltinPrefix, 0) == 0) {
    Scene scene = makeBuiltinScene(std::string_view(spec).substr(kBuiltinPrefix.size()));
    summarize(scene, report);
    return scene;
  }
  const std::string ext = lowercaseExtension(spec);
  if (ext == ".gltf" || ext == ".glb") return loadGltf(spec, &report);
  if (ext == ".obj") return loadObj(spec, &report);
  if (ext == ".off") return loadOff(spec, &report);

  std::string builtins;
  for (const std::string& n : builtinSceneNames()) builtins += ", " + n;
  throw SceneError(spec, "unsupported scene '" + spec + "' (use a .gltf, .glb, .obj or .off file, or one of the" +
                             " built-in scenes" + builtins.substr(1) + ")");
}

Scene loadScene(const std::string& spec) {
  SceneLoadReport report;
  return loadScene(spec, report);
}

}  // namespace ht
