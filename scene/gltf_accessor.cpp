// gltf_accessor.cpp - accessor validation and decoding (glTF 2.0 spec, "Binary Data Storage": accessors, bufferViews,
// buffers).
#include "scene/gltf_accessor.h"

#include <algorithm>
#include <cstring>
#include <limits>

#include "common/error.h"

namespace ht {
namespace {

constexpr std::size_t kMaxZeroFilledElements = std::size_t{1} << 24;

std::size_t componentBytes(int componentType) {
  switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return 4;
    default: return 0;  // includes DOUBLE and INT, which glTF 2.0 does not allow in accessors
  }
}

int componentsOf(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR: return 1;
    case TINYGLTF_TYPE_VEC2: return 2;
    case TINYGLTF_TYPE_VEC3: return 3;
    case TINYGLTF_TYPE_VEC4: return 4;
    default: return 0;  // matrices are not vertex attributes
  }
}

std::string typeName(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR: return "SCALAR";
    case TINYGLTF_TYPE_VEC2: return "VEC2";
    case TINYGLTF_TYPE_VEC3: return "VEC3";
    case TINYGLTF_TYPE_VEC4: return "VEC4";
    default: return "type " + std::to_string(type);
  }
}

// Decodes one component to float. Normalized integers follow the glTF 2.0 spec's decoding equations (section
// "Animations", repeated in the KHR_mesh_quantization README): u8 c/255, i8 max(c/127, -1), u16 c/65535, i16
// max(c/32767, -1).
float decodeComponent(const unsigned char* p, int componentType, bool normalized) {
  switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_FLOAT: {
      float v;
      std::memcpy(&v, p, 4);
      return v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return normalized ? p[0] / 255.0f : float(p[0]);
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
      const auto c = static_cast<signed char>(p[0]);
      return normalized ? std::max(c / 127.0f, -1.0f) : float(c);
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      std::uint16_t c;
      std::memcpy(&c, p, 2);
      return normalized ? c / 65535.0f : float(c);
    }
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
      std::int16_t c;
      std::memcpy(&c, p, 2);
      return normalized ? std::max(c / 32767.0f, -1.0f) : float(c);
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
      std::uint32_t c;
      std::memcpy(&c, p, 4);
      return float(c);
    }
    default: return 0.0f;  // unreachable: component types are validated first
  }
}

std::uint32_t decodeIndex(const unsigned char* p, int componentType) {
  switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return p[0];
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      std::uint16_t c;
      std::memcpy(&c, p, 2);
      return c;
    }
    default: {
      std::uint32_t c;
      std::memcpy(&c, p, 4);
      return c;
    }
  }
}

const tinygltf::Accessor& checkedAccessor(const tinygltf::Model& model, int index, const AccessorUse& use) {
  if (index < 0 || static_cast<std::size_t>(index) >= model.accessors.size())
    throw SceneError(use.file, use.what + ": accessor " + std::to_string(index) + " does not exist (the file has " +
                                   std::to_string(model.accessors.size()) + " accessors; fix the reference)");
  const tinygltf::Accessor& a = model.accessors[static_cast<std::size_t>(index)];
  if (componentBytes(a.componentType) == 0)
    throw SceneError(use.file, use.what + ": accessor " + std::to_string(index) + " has invalid componentType " +
                                   std::to_string(a.componentType) + " (glTF allows 5120-5123, 5125, 5126)");
  return a;
}

// A strided view of elementBytes-sized elements inside one buffer, range-checked at construction.
struct ElementSpan {
  const unsigned char* base = nullptr;
  std::size_t stride = 0;
};

// Checks that `count` elements of `elementBytes` bytes at `byteOffset` (stride from the bufferView, or
// tightly packed) lie inside bufferView `viewIndex`, which must lie inside its buffer.
ElementSpan checkedSpan(const tinygltf::Model& model, int viewIndex, std::size_t byteOffset, std::size_t count,
                        std::size_t elementBytes, bool allowStride, const AccessorUse& use, const std::string& role) {
  const std::string who = use.what + " (" + role + ")";
  if (viewIndex < 0 || static_cast<std::size_t>(viewIndex) >= model.bufferViews.size())
    throw SceneError(use.file, who + ": bufferView " + std::to_string(viewIndex) + " does not exist (the file has " +
                                   std::to_string(model.bufferViews.size()) + " bufferViews; fix the accessor)");
  const tinygltf::BufferView& view = model.bufferViews[static_cast<std::size_t>(viewIndex)];
  if (view.buffer < 0 || static_cast<std::size_t>(view.buffer) >= model.buffers.size())
    throw SceneError(use.file, who + ": bufferView " + std::to_string(viewIndex) + " refers to missing buffer " +
                                   std::to_string(view.buffer) + " (fix the bufferView)");
  const std::size_t bufferBytes = model.buffers[static_cast<std::size_t>(view.buffer)].data.size();
  if (view.byteOffset > bufferBytes || view.byteLength > bufferBytes - view.byteOffset)
    throw SceneError(use.file, who + ": bufferView " + std::to_string(viewIndex) + " spans bytes [" +
                                   std::to_string(view.byteOffset) + ", " + std::to_string(view.byteOffset) + "+" +
                                   std::to_string(view.byteLength) + ") but buffer " + std::to_string(view.buffer) +
                                   " has " + std::to_string(bufferBytes) +
                                   " bytes (the buffer is too short or the file truncated)");
  const std::size_t stride = (allowStride && view.byteStride != 0) ? view.byteStride : elementBytes;
  if (stride < elementBytes)
    throw SceneError(use.file, who + ": byteStride " + std::to_string(stride) + " is smaller than the element size " +
                                   std::to_string(elementBytes) + " (fix bufferView " + std::to_string(viewIndex) +
                                   ")");
  // Last element ends at byteOffset + stride * (count - 1) + elementBytes; test without overflow.
  const std::size_t available = view.byteLength;
  const bool fits = count == 0 || (byteOffset <= available && elementBytes <= available - byteOffset &&
                                   (count - 1) <= (available - byteOffset - elementBytes) / stride);
  if (!fits)
    throw SceneError(use.file, who + ": " + std::to_string(count) + " elements of " + std::to_string(elementBytes) +
                                   " bytes (stride " + std::to_string(stride) + ") at offset " +
                                   std::to_string(byteOffset) + " do not fit in bufferView " +
                                   std::to_string(viewIndex) + " of " + std::to_string(available) +
                                   " bytes (the buffer is too short for its accessor)");
  const unsigned char* bufferData = model.buffers[static_cast<std::size_t>(view.buffer)].data.data();
  return {bufferData + view.byteOffset + byteOffset, stride};
}

// Applies a sparse accessor's substitutions (glTF 2.0 spec, "Sparse Accessors") to `values`.
void applySparse(const tinygltf::Model& model, const tinygltf::Accessor& a, int components, bool normalized,
                 std::vector<float>& values, const AccessorUse& use) {
  const auto& sparse = a.sparse;
  if (sparse.count < 0 || static_cast<std::size_t>(sparse.count) > a.count)
    throw SceneError(use.file, use.what + ": sparse.count " + std::to_string(sparse.count) +
                                   " exceeds the accessor count " + std::to_string(a.count) + " (fix the file)");
  const auto n = static_cast<std::size_t>(sparse.count);
  const int indexType = sparse.indices.componentType;
  if (indexType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && indexType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
      indexType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
    throw SceneError(use.file, use.what + ": sparse.indices.componentType " + std::to_string(indexType) +
                                   " is not an unsigned integer type (fix the file)");
  if (sparse.indices.byteOffset < 0 || sparse.values.byteOffset < 0)
    throw SceneError(use.file, use.what + ": negative sparse byteOffset (fix the file)");
  const std::size_t compBytes = componentBytes(a.componentType);
  const ElementSpan idx =
      checkedSpan(model, sparse.indices.bufferView, static_cast<std::size_t>(sparse.indices.byteOffset), n,
                  componentBytes(indexType), false, use, "sparse indices");
  const ElementSpan val =
      checkedSpan(model, sparse.values.bufferView, static_cast<std::size_t>(sparse.values.byteOffset), n,
                  compBytes * static_cast<std::size_t>(components), false, use, "sparse values");
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint32_t target = decodeIndex(idx.base + i * idx.stride, indexType);
    if (target >= a.count)
      throw SceneError(use.file, use.what + ": sparse index " + std::to_string(target) + " >= accessor count " +
                                     std::to_string(a.count) + " (fix the file)");
    for (int c = 0; c < components; ++c)
      values[target * static_cast<std::size_t>(components) + static_cast<std::size_t>(c)] = decodeComponent(
          val.base + i * val.stride + static_cast<std::size_t>(c) * compBytes, a.componentType, normalized);
  }
}

}  // namespace

std::size_t checkedAccessorCount(const tinygltf::Model& model, int index, const AccessorUse& use) {
  return checkedAccessor(model, index, use).count;
}

std::vector<float> readFloatAccessor(const tinygltf::Model& model, int index, int type, const AccessorUse& use,
                                     bool forceNormalized) {
  const tinygltf::Accessor& a = checkedAccessor(model, index, use);
  if (a.type != type)
    throw SceneError(use.file, use.what + ": accessor " + std::to_string(index) + " is " + typeName(a.type) +
                                   ", expected " + typeName(type) + " (fix the accessor type)");
  const int components = componentsOf(type);
  const bool normalized = a.normalized || (forceNormalized && a.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT);
  const std::size_t compBytes = componentBytes(a.componentType);
  const std::size_t elementBytes = compBytes * static_cast<std::size_t>(components);

  // With a bufferView the whole byte range is checked before the first read; without one the accessor is
  // all zeros plus optional sparse substitutions (spec, "Sparse Accessors"), and its count is capped because no
  // stored bytes bound it.
  ElementSpan span;
  if (a.bufferView >= 0)
    span = checkedSpan(model, a.bufferView, a.byteOffset, a.count, elementBytes, true, use,
                       "accessor " + std::to_string(index));
  else if (a.count > kMaxZeroFilledElements)
    throw SceneError(use.file, use.what + ": accessor " + std::to_string(index) + " has no bufferView and count " +
                                   std::to_string(a.count) + " (more than " + std::to_string(kMaxZeroFilledElements) +
                                   " zero-filled elements; fix the accessor)");
  std::vector<float> values(a.count * static_cast<std::size_t>(components), 0.0f);
  if (span.base)
    for (std::size_t i = 0; i < a.count; ++i)
      for (int c = 0; c < components; ++c)
        values[i * static_cast<std::size_t>(components) + static_cast<std::size_t>(c)] = decodeComponent(
            span.base + i * span.stride + static_cast<std::size_t>(c) * compBytes, a.componentType, normalized);
  if (a.sparse.isSparse) applySparse(model, a, components, normalized, values, use);
  return values;
}

std::vector<std::uint32_t> readIndexAccessor(const tinygltf::Model& model, int index, const AccessorUse& use) {
  const tinygltf::Accessor& a = checkedAccessor(model, index, use);
  if (a.type != TINYGLTF_TYPE_SCALAR)
    throw SceneError(use.file, use.what + ": index accessor " + std::to_string(index) + " is " + typeName(a.type) +
                                   ", expected SCALAR (fix the accessor)");
  const int ct = a.componentType;
  if (ct != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && ct != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
      ct != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
    throw SceneError(use.file, use.what + ": index accessor " + std::to_string(index) + " has componentType " +
                                   std::to_string(ct) +
                                   "; indices must be unsigned byte, short or int (5121, 5123, 5125)");
  if (a.sparse.isSparse)
    throw SceneError(use.file,
                     use.what + ": sparse index accessors are not supported (re-export without sparse indices)");
  const ElementSpan span = checkedSpan(model, a.bufferView, a.byteOffset, a.count, componentBytes(ct), true, use,
                                       "index accessor " + std::to_string(index));
  std::vector<std::uint32_t> indices(a.count);
  for (std::size_t i = 0; i < a.count; ++i) indices[i] = decodeIndex(span.base + i * span.stride, ct);
  return indices;
}

}  // namespace ht
