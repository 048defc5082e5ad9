// gltf_nodes.cpp - scene selection and node-hierarchy flattening (glTF 2.0 spec, "Scenes" and "Nodes and Hierarchy").
#include "scene/gltf_nodes.h"

#include <cmath>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

#include "common/error.h"

namespace ht {
namespace {

double finiteValue(double v, const std::string& file, const std::string& what) {
  if (!std::isfinite(v)) throw SceneError(file, what + " contains a non-finite number (fix the node transform)");
  return v;
}

void checkSize(const std::vector<double>& v, std::size_t n, const std::string& file, const std::string& what) {
  if (!v.empty() && v.size() != n)
    throw SceneError(file, what + " has " + std::to_string(v.size()) + " numbers, expected " + std::to_string(n) +
                               " (fix the node)");
}

void checkNodeIndex(int index, const tinygltf::Model& model, const std::string& file, const std::string& referrer) {
  if (index < 0 || static_cast<std::size_t>(index) >= model.nodes.size())
    throw SceneError(file, referrer + " refers to node " + std::to_string(index) +
                               ", which does not exist (the file has " + std::to_string(model.nodes.size()) +
                               " nodes; fix the reference)");
}

// Root nodes of the scene to render: default scene, else scene 0, else all nodes that are nobody's child.
std::vector<int> rootNodes(const tinygltf::Model& model, const std::string& file) {
  if (model.defaultScene >= 0 && static_cast<std::size_t>(model.defaultScene) >= model.scenes.size())
    throw SceneError(file, "'scene' = " + std::to_string(model.defaultScene) + " but the file has " +
                               std::to_string(model.scenes.size()) + " scenes (fix the default scene index)");
  if (!model.scenes.empty()) {
    const std::size_t chosen = model.defaultScene >= 0 ? static_cast<std::size_t>(model.defaultScene) : 0;
    return model.scenes[chosen].nodes;
  }
  std::vector<bool> isChild(model.nodes.size(), false);
  for (std::size_t i = 0; i < model.nodes.size(); ++i)
    for (int c : model.nodes[i].children) {
      checkNodeIndex(c, model, file, "node " + std::to_string(i) + " children");
      isChild[static_cast<std::size_t>(c)] = true;
    }
  std::vector<int> roots;
  for (std::size_t i = 0; i < model.nodes.size(); ++i)
    if (!isChild[i]) roots.push_back(static_cast<int>(i));
  return roots;
}

}  // namespace

glm::dmat4 localTransform(const tinygltf::Node& node, const std::string& file, int index) {
  const std::string what = "node " + std::to_string(index);
  checkSize(node.matrix, 16, file, what + " matrix");
  checkSize(node.translation, 3, file, what + " translation");
  checkSize(node.rotation, 4, file, what + " rotation");
  checkSize(node.scale, 3, file, what + " scale");
  if (!node.matrix.empty()) {
    glm::dmat4 m;
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r)  // glTF matrices are column-major, as GLM's m[column][row]
        m[c][r] = finiteValue(node.matrix[static_cast<std::size_t>(4 * c + r)], file, what + " matrix");
    return m;
  }
  glm::dmat4 t(1.0), r(1.0), s(1.0);
  if (!node.translation.empty())
    t[3] = glm::dvec4(finiteValue(node.translation[0], file, what + " translation"),
                      finiteValue(node.translation[1], file, what + " translation"),
                      finiteValue(node.translation[2], file, what + " translation"), 1.0);
  if (!node.rotation.empty()) {
    // glTF stores the unit quaternion as (x, y, z, w); glm::dquat's constructor takes (w, x, y, z).
    glm::dquat q(finiteValue(node.rotation[3], file, what + " rotation"),
                 finiteValue(node.rotation[0], file, what + " rotation"),
                 finiteValue(node.rotation[1], file, what + " rotation"),
                 finiteValue(node.rotation[2], file, what + " rotation"));
    const double len = glm::length(q);
    if (!(len > 0.0)) throw SceneError(file, what + " rotation is the zero quaternion (use [0, 0, 0, 1] for none)");
    r = glm::mat4_cast(q / len);
  }
  if (!node.scale.empty())
    s = glm::scale(glm::dmat4(1.0), glm::dvec3(finiteValue(node.scale[0], file, what + " scale"),
                                               finiteValue(node.scale[1], file, what + " scale"),
                                               finiteValue(node.scale[2], file, what + " scale")));
  return t * r *
         s;  // glTF 2.0 spec, Transformations: TRS is converted to matrices "postmultiplied in the T * R * S order"
}

std::vector<NodeInstance> flattenSceneNodes(const tinygltf::Model& model, const std::string& file) {
  std::vector<NodeInstance> out;
  std::vector<bool> visited(model.nodes.size(), false);
  std::vector<NodeInstance> stack;  // explicit stack: a hostile deep chain cannot overflow the call stack
  const std::vector<int> roots = rootNodes(model, file);
  for (auto it = roots.rbegin(); it != roots.rend(); ++it) {
    checkNodeIndex(*it, model, file, "the scene's node list");
    stack.push_back({*it, glm::dmat4(1.0)});
  }
  while (!stack.empty()) {
    NodeInstance parent = stack.back();
    stack.pop_back();
    const auto n = static_cast<std::size_t>(parent.node);
    if (visited[n])
      throw SceneError(file, "node " + std::to_string(parent.node) + " is reached twice: the node hierarchy " +
                                 "has a cycle or a shared child (each node may have one parent; fix the file)");
    visited[n] = true;
    const tinygltf::Node& node = model.nodes[n];
    const NodeInstance self{parent.node, parent.world * localTransform(node, file, parent.node)};
    out.push_back(self);
    for (auto c = node.children.rbegin(); c != node.children.rend(); ++c) {
      checkNodeIndex(*c, model, file, "node " + std::to_string(parent.node) + " children");
      stack.push_back({*c, self.world});
    }
  }
  return out;
}

}  // namespace ht
