// gltf_lights.cpp - KHR_lights_punctual (Khronos glTF extension README): a light sits at its node's origin
// and shines along the node's local -Z axis; point/spot intensity in candela, directional in lux.
#include "scene/gltf_lights.h"

#include <cmath>

#include "common/error.h"

namespace ht {
namespace {

float finite(double v, const std::string& file, const std::string& what) {
  if (!std::isfinite(v)) throw SceneError(file, what + " is not a finite number (fix the light)");
  return static_cast<float>(v);
}

Light convertLight(const tinygltf::Light& in, const std::string& file, const std::string& what) {
  Light out;
  if (in.type == "point")
    out.type = Light::Type::Point;
  else if (in.type == "spot")
    out.type = Light::Type::Spot;
  else if (in.type == "directional")
    out.type = Light::Type::Directional;
  else
    throw SceneError(file, what + " has type '" + in.type + "' (expected point, spot or directional)");
  if (!in.color.empty()) {
    if (in.color.size() != 3) throw SceneError(file, what + " color needs 3 numbers (fix the light)");
    out.color = {finite(in.color[0], file, what + " color"), finite(in.color[1], file, what + " color"),
                 finite(in.color[2], file, what + " color")};
  }
  out.intensity = finite(in.intensity, file, what + " intensity");
  out.range = finite(in.range, file, what + " range");
  out.innerConeAngle = finite(in.spot.innerConeAngle, file, what + " spot.innerConeAngle");
  out.outerConeAngle = finite(in.spot.outerConeAngle, file, what + " spot.outerConeAngle");
  return out;
}

}  // namespace

bool appendNodeLight(const tinygltf::Model& model, const NodeInstance& instance, Scene& scene,
                     const std::string& file) {
  const tinygltf::Node& node = model.nodes[static_cast<std::size_t>(instance.node)];
  const auto ext = node.extensions.find("KHR_lights_punctual");
  if (ext == node.extensions.end()) return false;
  const std::string what = "node " + std::to_string(instance.node) + " KHR_lights_punctual";
  if (!ext->second.IsObject() || !ext->second.Has("light") || !ext->second.Get("light").IsInt())
    throw SceneError(file, what + " needs an integer 'light' index (fix the node)");
  const int index = ext->second.Get("light").GetNumberAsInt();
  if (index < 0 || static_cast<std::size_t>(index) >= model.lights.size())
    throw SceneError(file, what + " refers to light " + std::to_string(index) + " but the file defines " +
                               std::to_string(model.lights.size()) + " lights (fix the index)");
  Light light = convertLight(model.lights[static_cast<std::size_t>(index)], file, "light " + std::to_string(index));

  // Position: the node origin in world space. Direction: the world image of local -Z (a direction, so
  // w = 0: translation does not apply), normalized.
  light.position = glm::vec3(instance.world * glm::dvec4(0.0, 0.0, 0.0, 1.0));
  const glm::dvec3 dir(instance.world * glm::dvec4(0.0, 0.0, -1.0, 0.0));
  const double len = glm::length(dir);
  if (!(len > 0.0) || !std::isfinite(len))
    throw SceneError(file, what + ": the node transform collapses the light direction (a zero scale; fix the node)");
  light.direction = glm::vec3(dir / len);
  scene.lights.push_back(light);
  return true;
}

}  // namespace ht
