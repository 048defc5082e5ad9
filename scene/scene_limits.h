// scene_limits.h - caps the loaders enforce before allocating, so a hostile or broken file is refused with a
// SceneError instead of exhausting memory (docs/SERVICE.md §6 "Loader limits").
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>

#include "common/error.h"

namespace ht::limits {

inline constexpr std::size_t kMaxTriangles = 50'000'000;        // per scene, after triangulation
inline constexpr std::uint32_t kMaxImageDimension = 16384;      // texture width and height
inline constexpr std::uintmax_t kMaxFileBytes = 2'000'000'000;  // scene file or external buffer/image (< 2^31:
                                                                // tinygltf takes unsigned int lengths)

inline constexpr std::uint64_t kMaxNodes = 1'000'000;             // glTF nodes in one file
inline constexpr std::uint64_t kMaxInstances = 1'000'000;         // mesh-bearing node instances after flattening
inline constexpr std::uint64_t kMaxTexturePixels = 512ull << 20;  // all decoded textures together (2 GiB RGBA8)

}  // namespace ht::limits

namespace ht {

// A scene over one of the caps (size, counts): refused before the memory is allocated. The daemon answers
// RESOURCE_EXHAUSTED, the CLI exits 1, both naming the file, the count and the limit.
class SceneLimitExceeded : public SceneError {
 public:
  using SceneError::SceneError;
};

// The count limits a load is held to, each checked from the file's headers (glTF accessor counts x instancing, node
// and image headers, OFF header counts; OBJ as its lines are read) before the memory for it is allocated. The CLI
// loads with these defaults; holotraced sets maxTriangles (and maxVertices = 3x) from limits.max_triangles.
struct SceneLimits {
  std::uint64_t maxTriangles = limits::kMaxTriangles;
  std::uint64_t maxVertices = 3 * limits::kMaxTriangles;
  std::uint64_t maxNodes = limits::kMaxNodes;
  std::uint64_t maxInstances = limits::kMaxInstances;
  std::uint64_t maxTexturePixels = limits::kMaxTexturePixels;
};

// "the scene has <count> <what>, more than the limit of <limit> (<fix>)" as a SceneLimitExceeded for `file`.
[[noreturn]] inline void throwOverLimit(const std::string& file, std::uint64_t count, const std::string& what,
                                        std::uint64_t limit, const std::string& fix) {
  throw SceneLimitExceeded(file, "the scene has " + std::to_string(count) + " " + what + ", more than the limit of " +
                                     std::to_string(limit) + " (" + fix + ")");
}

}  // namespace ht
