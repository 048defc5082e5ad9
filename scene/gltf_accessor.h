// gltf_accessor.h - (internal to ht_scene) bounds-checked reads of glTF accessors.
//
// Every index (accessor, bufferView, buffer) and byte range is validated before a byte is read; problems
// throw SceneError(file, "<what>: ... (how to fix)"), where <what> names the use, e.g.
// "mesh 0 primitive 1 POSITION".
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <tiny_gltf.h>

namespace ht {

struct AccessorUse {
  const std::string& file;
  std::string what;
};

// Number of elements of accessor `index` after checking the index and its component/element types.
std::size_t checkedAccessorCount(const tinygltf::Model& model, int index, const AccessorUse& use);

// Reads accessor `index` (element type `type`, e.g. TINYGLTF_TYPE_VEC3) as count * components floats.
// Integer components are normalized when the accessor says so (or `forceNormalized`, for attributes whose
// integer forms are always normalized such as TEXCOORD_n); sparse accessors are resolved.
std::vector<float> readFloatAccessor(const tinygltf::Model& model, int index, int type, const AccessorUse& use,
                                     bool forceNormalized = false);

// Reads an index accessor (SCALAR; unsigned byte, short or int).
std::vector<std::uint32_t> readIndexAccessor(const tinygltf::Model& model, int index, const AccessorUse& use);

}  // namespace ht
