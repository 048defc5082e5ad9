// gltf_loader.h - glTF 2.0 (.gltf with external or data-URI buffers, .glb) -> Scene, via tinygltf.
//
// What is loaded: the default scene (else scene 0, else every root node) with the node hierarchy's
// matrix or TRS transforms flattened to world space; TRIANGLES, TRIANGLE_STRIP and TRIANGLE_FAN primitives
// (indexed with u8/u16/u32 indices, or not indexed); NORMAL (transformed by the inverse transpose) and
// TEXCOORD_0 (float or normalized integers); winding flipped under negative-determinant transforms;
// materials (see gltf_materials.h) and KHR_lights_punctual lights placed by their nodes.
// Not loaded (counted or warned in the report): POINTS/LINES primitives, skins, morph targets, cameras,
// textures other than baseColorTexture.
//
// Hostile files: every index and byte range is checked, sizes above scene_limits.h are refused before
// allocating, unsupported `extensionsRequired` (e.g. Draco) are refused, external files must lie in the
// file's folder. Every failure throws SceneError(path, "what is wrong (how to fix)").
#pragma once
#include <string>

#include "scene/load_report.h"
#include "scene/scene.h"
#include "scene/scene_limits.h"
#include "scene/scene_source.h"

namespace ht {

Scene loadGltf(const std::string& path, SceneLoadReport* report = nullptr);
// From bytes read beforehand (scene_source.h): external files come only from `source`.
// Every count of `limits` is refused (SceneLimitExceeded) from the headers, before the memory is allocated.
Scene loadGltf(const SceneSource& source, SceneLoadReport* report = nullptr, const SceneLimits& limits = {});

}  // namespace ht
