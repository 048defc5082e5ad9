// gltf_nodes.h - (internal to ht_scene) choosing the glTF scene and flattening its node hierarchy.
#pragma once
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <tiny_gltf.h>

namespace ht {

struct NodeInstance {
  int node = -1;
  glm::dmat4 world{1.0};  // node-local -> world (parent chain applied), double precision
};

// The nodes of the default scene (glTF `scene`), else of scene 0, else every root node (a node that is no
// node's child), each with its world transform, parents before children. Throws SceneError for a missing
// scene/node index, a node reached twice (the hierarchy must be a forest) and non-finite transforms.
std::vector<NodeInstance> flattenSceneNodes(const tinygltf::Model& model, const std::string& file);

// A node's local transform: `matrix` (column-major) or T * R * S (glTF 2.0 spec, Nodes > "Transformations").
glm::dmat4 localTransform(const tinygltf::Node& node, const std::string& file, int index);

}  // namespace ht
