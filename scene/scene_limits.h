// scene_limits.h - caps the loaders enforce before allocating, so a hostile or broken file is refused with a
// SceneError instead of exhausting memory (docs/SERVICE.md §6 "Loader limits").
#pragma once
#include <cstddef>
#include <cstdint>

namespace ht::limits {

inline constexpr std::size_t kMaxTriangles = 50'000'000;        // per scene, after triangulation
inline constexpr std::uint32_t kMaxImageDimension = 16384;      // texture width and height
inline constexpr std::uintmax_t kMaxFileBytes = 2'000'000'000;  // scene file or external buffer/image (< 2^31:
                                                                // tinygltf takes unsigned int lengths)

}  // namespace ht::limits
