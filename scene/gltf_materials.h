// gltf_materials.h - (internal to ht_scene) glTF materials and their base-colour textures -> Scene.
#pragma once
#include <string>

#include <tiny_gltf.h>

#include "scene/load_report.h"
#include "scene/scene.h"

namespace ht {

// Appends one Material per glTF material (same order, so glTF material i is scene.materials[i] when the
// scene starts empty) and decodes the base-colour textures they use into scene.textures (sRGB -> linear).
// Reads pbrMetallicRoughness (baseColorFactor, baseColorTexture, metallicFactor, roughnessFactor),
// emissiveFactor, KHR_materials_emissive_strength, KHR_materials_transmission and KHR_materials_ior.
void appendGltfMaterials(const tinygltf::Model& model, Scene& scene, const std::string& file, SceneLoadReport& report);

// Decodes a tinygltf image (8- or 16-bit, 1-4 channels) into a linear RGBA texture: colour channels go
// through the sRGB decoding curve, alpha stays linear.
Texture decodeSrgbTexture(const tinygltf::Image& image, const std::string& file, const std::string& what);

}  // namespace ht
