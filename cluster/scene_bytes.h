// scene_bytes.h - a loaded Scene as bytes and back: rank 0 of a cluster render loads the scene (glTF with its
// buffers and textures, OBJ, built-in) and broadcasts these bytes, so no rank needs the scene files or a shared
// filesystem; each rank builds its own BVH from the scene it decodes. The encoding is this build's own (ranks run
// the same build, rank_identity.h): fields in declaration order, little-endian as in memory, sizes as uint64.
#pragma once
#include <cstdint>
#include <span>
#include <vector>

#include "scene/scene.h"

namespace ht::cluster {

std::vector<std::uint8_t> encodeScene(const Scene& scene);

// Throws ClusterError when the bytes end early, a size exceeds what is left, or bytes remain after the scene.
Scene decodeScene(std::span<const std::uint8_t> bytes);

}  // namespace ht::cluster
