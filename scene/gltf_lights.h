// gltf_lights.h - (internal to ht_scene) KHR_lights_punctual lights placed by their nodes.
#pragma once
#include <string>

#include <tiny_gltf.h>

#include "scene/gltf_nodes.h"
#include "scene/scene.h"

namespace ht {

// If the instance's node carries `extensions.KHR_lights_punctual.light`, appends that light to
// scene.lights with its world position and direction and returns true.
bool appendNodeLight(const tinygltf::Model& model, const NodeInstance& instance, Scene& scene, const std::string& file);

}  // namespace ht
