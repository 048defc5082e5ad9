// load_report.h - what a loader did with a file: counts the caller may print or test, and the non-fatal
// problems it worked around. Fatal problems are SceneErrors instead (common/error.h).
#pragma once
#include <cstddef>
#include <string>
#include <vector>

namespace ht {

struct SceneLoadReport {
  std::size_t triangles = 0;          // triangles appended to the Scene
  std::size_t vertices = 0;           // vertices appended to the Scene
  std::size_t primitives = 0;         // glTF primitives turned into triangles (1 for OBJ/OFF)
  std::size_t skippedPrimitives = 0;  // POINTS / LINES / LINE_LOOP / LINE_STRIP primitives (not rendered)
  std::size_t nonFiniteVertices = 0;  // positions with a NaN/Inf coordinate (kept; the BVH builder drops them)
  std::size_t textures = 0;           // decoded textures
  std::size_t lights = 0;             // punctual lights placed in the scene
  std::vector<std::string> warnings;  // tinygltf warnings and ignored, non-required features
};

}  // namespace ht
