// gltf_materials.cpp - glTF 2.0 metallic-roughness materials (spec, "Materials") and the KHR material extensions.
#include "scene/gltf_materials.h"

#include <cmath>
#include <map>

#include "common/error.h"
#include "scene/color.h"

namespace ht {
namespace {

struct MaterialContext {
  const tinygltf::Model& model;
  Scene& scene;
  const std::string& file;
  SceneLoadReport& report;
  std::map<int, int> sceneTextureOfGltfTexture;  // decode each glTF texture once
};

float finiteFactor(double value, const std::string& file, const std::string& what) {
  if (!std::isfinite(value)) throw SceneError(file, what + " is not a finite number (fix the material)");
  return static_cast<float>(value);
}

glm::vec3 colorFactor(const std::vector<double>& v, std::size_t expectedSize, glm::vec3 fallback,
                      const std::string& file, const std::string& what) {
  if (v.empty()) return fallback;
  if (v.size() != expectedSize)
    throw SceneError(file, what + " has " + std::to_string(v.size()) + " components, expected " +
                               std::to_string(expectedSize) + " (fix the material)");
  return {finiteFactor(v[0], file, what), finiteFactor(v[1], file, what), finiteFactor(v[2], file, what)};
}

// A number inside a material extension object, e.g. KHR_materials_ior.ior; `fallback` when absent.
float extensionNumber(const tinygltf::Material& m, const std::string& extension, const std::string& key, float fallback,
                      const std::string& file, const std::string& what) {
  const auto ext = m.extensions.find(extension);
  if (ext == m.extensions.end() || !ext->second.IsObject() || !ext->second.Has(key)) return fallback;
  const tinygltf::Value& v = ext->second.Get(key);
  if (!v.IsNumber()) throw SceneError(file, what + " " + extension + "." + key + " is not a number (fix the material)");
  return finiteFactor(v.GetNumberAsDouble(), file, what + " " + extension + "." + key);
}

float channel(const unsigned char* p, int bits) {
  if (bits == 16) return static_cast<float>(p[0] | (p[1] << 8)) / 65535.0f;  // stb returns native (LE) uint16
  return static_cast<float>(p[0]) / 255.0f;
}

int sceneTextureFor(MaterialContext& ctx, int gltfTexture, const std::string& what) {
  if (auto it = ctx.sceneTextureOfGltfTexture.find(gltfTexture); it != ctx.sceneTextureOfGltfTexture.end())
    return it->second;
  if (gltfTexture < 0 || static_cast<std::size_t>(gltfTexture) >= ctx.model.textures.size())
    throw SceneError(ctx.file, what + ": texture " + std::to_string(gltfTexture) + " does not exist (the file has " +
                                   std::to_string(ctx.model.textures.size()) + " textures; fix the reference)");
  const int source = ctx.model.textures[static_cast<std::size_t>(gltfTexture)].source;
  if (source < 0 || static_cast<std::size_t>(source) >= ctx.model.images.size())
    throw SceneError(ctx.file, what + ": texture " + std::to_string(gltfTexture) + " has no valid image source " +
                                   std::to_string(source) + " (KHR_texture_basisu/EXT_texture_webp are not supported;" +
                                   " provide a PNG or JPEG source)");
  const tinygltf::Image& image = ctx.model.images[static_cast<std::size_t>(source)];
  Texture texture = decodeSrgbTexture(image, ctx.file, "image " + std::to_string(source));
  ctx.scene.textures.push_back(std::move(texture));
  const int index = static_cast<int>(ctx.scene.textures.size() - 1);
  ctx.sceneTextureOfGltfTexture[gltfTexture] = index;
  return index;
}

void warnUnsupportedTextures(const tinygltf::Material& m, SceneLoadReport& report, const std::string& what) {
  if (m.pbrMetallicRoughness.metallicRoughnessTexture.index >= 0 || m.normalTexture.index >= 0 ||
      m.emissiveTexture.index >= 0 || m.occlusionTexture.index >= 0)
    report.warnings.push_back(what + ": metallic-roughness, normal, emissive and occlusion textures are ignored");
  if (m.pbrMetallicRoughness.baseColorTexture.texCoord != 0)
    report.warnings.push_back(what + ": baseColorTexture uses TEXCOORD_" +
                              std::to_string(m.pbrMetallicRoughness.baseColorTexture.texCoord) +
                              "; only TEXCOORD_0 is loaded");
}

Material convertMaterial(MaterialContext& ctx, const tinygltf::Material& m, std::size_t index) {
  const std::string what = "material " + std::to_string(index);
  const tinygltf::PbrMetallicRoughness& pbr = m.pbrMetallicRoughness;
  Material out;
  out.name = m.name;
  out.baseColor = colorFactor(pbr.baseColorFactor, 4, glm::vec3(1.0f), ctx.file, what + " baseColorFactor");
  out.metallic = finiteFactor(pbr.metallicFactor, ctx.file, what + " metallicFactor");
  out.roughness = finiteFactor(pbr.roughnessFactor, ctx.file, what + " roughnessFactor");
  // Emitted radiance = emissiveFactor * emissiveStrength (KHR_materials_emissive_strength README).
  const float strength =
      extensionNumber(m, "KHR_materials_emissive_strength", "emissiveStrength", 1.0f, ctx.file, what);
  out.emissive = colorFactor(m.emissiveFactor, 3, glm::vec3(0.0f), ctx.file, what + " emissiveFactor") * strength;
  out.transmission = extensionNumber(m, "KHR_materials_transmission", "transmissionFactor", 0.0f, ctx.file, what);
  out.ior = extensionNumber(m, "KHR_materials_ior", "ior", 1.5f, ctx.file, what);
  if (pbr.baseColorTexture.index >= 0) out.baseColorTexture = sceneTextureFor(ctx, pbr.baseColorTexture.index, what);
  warnUnsupportedTextures(m, ctx.report, what);
  return out;
}

}  // namespace

Texture decodeSrgbTexture(const tinygltf::Image& image, const std::string& file, const std::string& what) {
  if (image.image.empty() || image.width <= 0 || image.height <= 0)
    throw SceneError(file,
                     what + (image.uri.empty() ? std::string() : " ('" + image.uri + "')") +
                         " has no decoded pixels (the image file is missing or unreadable; put it next to the .gltf)");
  const int comps = image.component;
  const int bits = image.bits;
  if (comps < 1 || comps > 4 || (bits != 8 && bits != 16))
    throw SceneError(file, what + ": " + std::to_string(comps) + " channels of " + std::to_string(bits) +
                               " bits are not supported (use an 8- or 16-bit PNG or a JPEG)");
  const auto w = static_cast<std::size_t>(image.width), h = static_cast<std::size_t>(image.height);
  const std::size_t texelBytes = static_cast<std::size_t>(comps * bits / 8);
  if (image.image.size() != w * h * texelBytes)
    throw SceneError(file, what + ": decoded size does not match " + std::to_string(w) + " x " + std::to_string(h) +
                               " (corrupt image; re-export it)");
  Texture t;
  t.name = image.name.empty() ? image.uri : image.name;
  t.width = static_cast<std::uint32_t>(w);
  t.height = static_cast<std::uint32_t>(h);
  t.texels.resize(w * h);
  const std::size_t channelBytes = static_cast<std::size_t>(bits / 8);
  for (std::size_t i = 0; i < w * h; ++i) {
    const unsigned char* p = image.image.data() + i * texelBytes;
    float c[4] = {0, 0, 0, 1};
    for (int k = 0; k < comps; ++k) c[k] = channel(p + static_cast<std::size_t>(k) * channelBytes, bits);
    // 1 channel = grey, 2 = grey + alpha (stb_image channel conventions).
    const glm::vec3 encoded = comps <= 2 ? glm::vec3(c[0]) : glm::vec3(c[0], c[1], c[2]);
    const float alpha = comps == 2 ? c[1] : c[3];
    t.texels[i] = {srgbToLinear(encoded.x), srgbToLinear(encoded.y), srgbToLinear(encoded.z), alpha};
  }
  return t;
}

void appendGltfMaterials(const tinygltf::Model& model, Scene& scene, const std::string& file, SceneLoadReport& report) {
  MaterialContext ctx{model, scene, file, report, {}};
  for (std::size_t i = 0; i < model.materials.size(); ++i)
    scene.materials.push_back(convertMaterial(ctx, model.materials[i], i));
}

}  // namespace ht
