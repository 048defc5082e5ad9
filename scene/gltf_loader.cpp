// gltf_loader.cpp - glTF 2.0 meshes -> world-space triangle soup (glTF 2.0 specification, section "Meshes").
#include "scene/gltf_loader.h"

#include <cmath>
#include <string>
#include <unordered_set>
#include <utility>

#include "common/error.h"
#include "scene/convex_sides.h"
#include "scene/gltf_accessor.h"
#include "scene/gltf_file.h"
#include "scene/gltf_lights.h"
#include "scene/gltf_materials.h"
#include "scene/gltf_nodes.h"
#include "scene/scene_limits.h"

namespace ht {
namespace {

// One primitive placed by one node, in world space, with indices local to it.
struct PrimitiveGeometry {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;    // empty: the primitive has none (or they did not survive the transform)
  std::vector<glm::vec2> texcoords;  // empty: none
  std::vector<glm::uvec3> triangles;
  std::uint32_t material = 0;
  std::uint32_t node = 0;  // index into Scene::nodes of the node instance it belongs to
};

struct LoadContext {
  const tinygltf::Model& model;
  const std::string& file;
  SceneLoadReport& report;
  Scene& scene;
  const SceneLimits& limits;
  int defaultMaterial = -1;                   // created on first use by a primitive without material
  std::unordered_set<std::string> nodeNames;  // Scene::nodes names so far (kept unique; files may repeat names)
};

bool isTriangleMode(int mode) {
  return mode == TINYGLTF_MODE_TRIANGLES || mode == TINYGLTF_MODE_TRIANGLE_STRIP || mode == TINYGLTF_MODE_TRIANGLE_FAN;
}

std::size_t triangleCount(int mode, std::size_t vertexRefs) {
  if (mode == TINYGLTF_MODE_TRIANGLES) return vertexRefs / 3;
  return vertexRefs >= 3 ? vertexRefs - 2 : 0;  // strips and fans
}

std::string primitiveName(int mesh, std::size_t primitive) {
  return "mesh " + std::to_string(mesh) + " primitive " + std::to_string(primitive);
}

int attribute(const tinygltf::Primitive& p, const char* name) {
  const auto it = p.attributes.find(name);
  return it == p.attributes.end() ? -1 : it->second;
}

const tinygltf::Mesh& checkedMesh(const LoadContext& ctx, int mesh, int node) {
  if (mesh < 0 || static_cast<std::size_t>(mesh) >= ctx.model.meshes.size())
    throw SceneError(ctx.file, "node " + std::to_string(node) + " refers to mesh " + std::to_string(mesh) +
                                   ", which does not exist (the file has " + std::to_string(ctx.model.meshes.size()) +
                                   " meshes; fix the node)");
  return ctx.model.meshes[static_cast<std::size_t>(mesh)];
}

// Refuses scenes whose instance, triangle or vertex total (over all mesh instances) exceeds ctx.limits, using only
// node and accessor counts, before any geometry is read or allocated: a small file that instances one mesh
// thousands of times is refused here, not after loading gigabytes.
void checkSizeBudget(const LoadContext& ctx, const std::vector<NodeInstance>& instances) {
  std::uint64_t triangles = 0, vertices = 0, meshInstances = 0;
  for (const NodeInstance& inst : instances) {
    const tinygltf::Node& node = ctx.model.nodes[static_cast<std::size_t>(inst.node)];
    if (node.mesh < 0) continue;
    if (++meshInstances > ctx.limits.maxInstances)
      throwOverLimit(ctx.file, meshInstances, "mesh instances or more", ctx.limits.maxInstances,
                     "instance fewer meshes");
    const tinygltf::Mesh& mesh = checkedMesh(ctx, node.mesh, inst.node);
    for (std::size_t p = 0; p < mesh.primitives.size(); ++p) {
      const tinygltf::Primitive& prim = mesh.primitives[p];
      if (!isTriangleMode(prim.mode)) continue;
      const AccessorUse use{ctx.file, primitiveName(node.mesh, p) + " POSITION"};
      const int position = attribute(prim, "POSITION");
      if (position < 0)
        throw SceneError(ctx.file,
                         primitiveName(node.mesh, p) + " has no POSITION attribute (every primitive needs one)");
      const std::size_t nv = checkedAccessorCount(ctx.model, position, use);
      const std::size_t refs =
          prim.indices >= 0
              ? checkedAccessorCount(ctx.model, prim.indices, {ctx.file, primitiveName(node.mesh, p) + " indices"})
              : nv;
      triangles += triangleCount(prim.mode, refs);
      vertices += nv;
      if (triangles > ctx.limits.maxTriangles)
        throwOverLimit(ctx.file, triangles, "triangles or more after instancing (from the accessor counts)",
                       ctx.limits.maxTriangles, "simplify or decimate it");
      if (vertices > ctx.limits.maxVertices)
        throwOverLimit(ctx.file, vertices, "vertices or more after instancing (from the accessor counts)",
                       ctx.limits.maxVertices, "simplify or decimate it");
    }
  }
}

// Vertex references -> triangles (glTF 2.0 spec, Meshes > "Topology types" table):
//   TRIANGLES: p_i = {v_3i, v_3i+1, v_3i+2}
//   TRIANGLE_STRIP: p_i = {v_i, v_(i+(1+i%2)), v_(i+(2-i%2))}
//   TRIANGLE_FAN: p_i = {v_(i+1), v_(i+2), v_0}
std::vector<glm::uvec3> assembleTriangles(int mode, const std::vector<std::uint32_t>& v) {
  std::vector<glm::uvec3> tris;
  const std::size_t n = triangleCount(mode, v.size());
  tris.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    if (mode == TINYGLTF_MODE_TRIANGLES)
      tris.push_back({v[3 * i], v[3 * i + 1], v[3 * i + 2]});
    else if (mode == TINYGLTF_MODE_TRIANGLE_STRIP)
      tris.push_back({v[i], v[i + 1 + i % 2], v[i + 2 - i % 2]});
    else
      tris.push_back({v[i + 1], v[i + 2], v[0]});
  }
  return tris;
}

std::vector<std::uint32_t> vertexReferences(const LoadContext& ctx, const tinygltf::Primitive& prim,
                                            std::size_t vertexCount, const std::string& what) {
  if (prim.indices < 0) {
    std::vector<std::uint32_t> refs(vertexCount);
    for (std::size_t i = 0; i < vertexCount; ++i) refs[i] = static_cast<std::uint32_t>(i);
    return refs;
  }
  std::vector<std::uint32_t> refs = readIndexAccessor(ctx.model, prim.indices, {ctx.file, what + " indices"});
  for (std::size_t i = 0; i < refs.size(); ++i)
    if (refs[i] >= vertexCount)
      throw SceneError(ctx.file, what + ": index " + std::to_string(i) + " = " + std::to_string(refs[i]) +
                                     " is out of range (POSITION has " + std::to_string(vertexCount) +
                                     " vertices; the indices or the vertex data are corrupt)");
  return refs;
}

std::uint32_t materialOf(LoadContext& ctx, const tinygltf::Primitive& prim, const std::string& what) {
  if (prim.material >= 0) {
    if (static_cast<std::size_t>(prim.material) >= ctx.model.materials.size())
      throw SceneError(ctx.file, what + " refers to material " + std::to_string(prim.material) + " but the file has " +
                                     std::to_string(ctx.model.materials.size()) + " materials (fix the reference)");
    return static_cast<std::uint32_t>(prim.material);  // glTF material i is scene.materials[i]
  }
  if (ctx.defaultMaterial < 0) {
    Material m;
    m.name = "default";
    ctx.scene.materials.push_back(m);
    ctx.defaultMaterial = static_cast<int>(ctx.scene.materials.size() - 1);
  }
  return static_cast<std::uint32_t>(ctx.defaultMaterial);
}

template <class Vec>
std::vector<Vec> toVectors(const std::vector<float>& flat) {
  constexpr int n = Vec::length();
  std::vector<Vec> out(flat.size() / n);
  for (std::size_t i = 0; i < out.size(); ++i)
    for (int c = 0; c < n; ++c) out[i][c] = flat[i * n + static_cast<std::size_t>(c)];
  return out;
}

void checkAttributeCount(const LoadContext& ctx, std::size_t count, std::size_t vertexCount, const std::string& what) {
  if (count != vertexCount)
    throw SceneError(ctx.file, what + " has " + std::to_string(count) + " elements but POSITION has " +
                                   std::to_string(vertexCount) +
                                   " (all attributes of a primitive need the same count)");
}

// Positions by the world matrix; normals by its inverse transpose (normals are covectors: n' = M^-T n keeps
// n' . t' = 0 for every transformed tangent t' = M t; pbrt-v4 "Applying Transformations: Normals"). A primitive whose
// normals do not survive (singular matrix, zero normals) falls back to flat normals.
void transformToWorld(PrimitiveGeometry& g, const glm::dmat4& world, SceneLoadReport& report, const std::string& what) {
  for (glm::vec3& p : g.positions) p = glm::vec3(world * glm::dvec4(glm::dvec3(p), 1.0));
  if (g.normals.empty()) return;
  const glm::dmat3 normalMatrix = glm::transpose(glm::inverse(glm::dmat3(world)));
  for (glm::vec3& n : g.normals) {
    const glm::dvec3 t = normalMatrix * glm::dvec3(n);
    const double len = glm::length(t);
    if (!(len > 0.0) || !std::isfinite(len)) {
      report.warnings.push_back(what + ": zero or non-finite normals after the node transform; using flat normals");
      g.normals.clear();
      return;
    }
    n = glm::vec3(t / len);
  }
}

PrimitiveGeometry readPrimitive(LoadContext& ctx, const tinygltf::Primitive& prim, const glm::dmat4& world,
                                const std::string& what) {
  PrimitiveGeometry g;
  g.positions = toVectors<glm::vec3>(
      readFloatAccessor(ctx.model, attribute(prim, "POSITION"), TINYGLTF_TYPE_VEC3, {ctx.file, what + " POSITION"}));
  const std::size_t nv = g.positions.size();
  if (const int a = attribute(prim, "NORMAL"); a >= 0) {
    g.normals = toVectors<glm::vec3>(readFloatAccessor(ctx.model, a, TINYGLTF_TYPE_VEC3, {ctx.file, what + " NORMAL"}));
    checkAttributeCount(ctx, g.normals.size(), nv, what + " NORMAL");
  }
  if (const int a = attribute(prim, "TEXCOORD_0"); a >= 0) {
    // TEXCOORD_n integer forms are always normalized (glTF 2.0 spec, Meshes > attribute table).
    g.texcoords = toVectors<glm::vec2>(
        readFloatAccessor(ctx.model, a, TINYGLTF_TYPE_VEC2, {ctx.file, what + " TEXCOORD_0"}, true));
    checkAttributeCount(ctx, g.texcoords.size(), nv, what + " TEXCOORD_0");
  }
  g.triangles = assembleTriangles(prim.mode, vertexReferences(ctx, prim, nv, what));
  g.material = materialOf(ctx, prim, what);
  if (!prim.targets.empty()) ctx.report.warnings.push_back(what + ": morph targets ignored (base shape loaded)");

  transformToWorld(g, world, ctx.report, what);
  // A mirroring transform (negative determinant) turns counter-clockwise into clockwise: swap two corners
  // so front faces stay counter-clockwise (glTF 2.0 spec, Meshes: for triangle topologies "the determinant
  // of the node's global transform defines the winding order").
  if (glm::determinant(glm::dmat3(world)) < 0.0)
    for (glm::uvec3& t : g.triangles) std::swap(t.y, t.z);
  return g;
}

// Gives a primitive without normals one vertex per triangle corner carrying the face normal (glTF 2.0
// spec, Meshes: "When normals are not specified, client implementations MUST calculate flat normals").
void makeFlat(PrimitiveGeometry& g) {
  PrimitiveGeometry flat;
  flat.material = g.material;
  flat.node = g.node;
  const bool uv = !g.texcoords.empty();
  for (const glm::uvec3& t : g.triangles) {
    const glm::vec3 a = g.positions[t.x], b = g.positions[t.y], c = g.positions[t.z];
    glm::vec3 n = glm::cross(b - a, c - a);
    const float len = glm::length(n);
    n = (len > 0.0f && std::isfinite(len)) ? n / len : glm::vec3(0.0f, 0.0f, 1.0f);  // degenerate: BVH drops it
    const auto base = static_cast<std::uint32_t>(flat.positions.size());
    for (int k = 0; k < 3; ++k) {
      flat.positions.push_back(g.positions[t[k]]);
      flat.normals.push_back(n);
      if (uv) flat.texcoords.push_back(g.texcoords[t[k]]);
    }
    flat.triangles.push_back({base, base + 1, base + 2});
  }
  g = std::move(flat);
}

// Appends all primitives; per-vertex arrays stay parallel: if any primitive has normals (texcoords), every
// primitive gets them (flat normals, texcoord (0, 0)).
void appendGeometry(Scene& scene, std::vector<PrimitiveGeometry>& prims, SceneLoadReport& report) {
  bool anyNormals = false, anyUv = false;
  for (const auto& g : prims) {
    anyNormals |= !g.normals.empty();
    anyUv |= !g.texcoords.empty();
  }
  for (PrimitiveGeometry& g : prims) {
    if (anyNormals && g.normals.empty()) makeFlat(g);
    if (anyUv && g.texcoords.empty()) g.texcoords.assign(g.positions.size(), glm::vec2(0.0f));
    const auto base = static_cast<std::uint32_t>(scene.positions.size());
    SceneNode& node = scene.nodes[g.node];  // a node's primitives are consecutive
    if (node.vertexCount == 0 && node.triangleCount == 0) {
      node.firstVertex = base;
      node.firstTriangle = static_cast<std::uint32_t>(scene.triangles.size());
    }
    node.vertexCount += static_cast<std::uint32_t>(g.positions.size());
    node.triangleCount += static_cast<std::uint32_t>(g.triangles.size());
    for (const glm::vec3& p : g.positions)
      if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) ++report.nonFiniteVertices;
    scene.positions.insert(scene.positions.end(), g.positions.begin(), g.positions.end());
    if (anyNormals) scene.normals.insert(scene.normals.end(), g.normals.begin(), g.normals.end());
    if (anyUv) scene.texcoords.insert(scene.texcoords.end(), g.texcoords.begin(), g.texcoords.end());
    for (const glm::uvec3& t : g.triangles) {
      scene.triangles.push_back(t + glm::uvec3(base));
      scene.triangleMaterial.push_back(g.material);
    }
    g = PrimitiveGeometry{};  // release memory as we go
  }
}

void readNodeMeshes(LoadContext& ctx, const NodeInstance& inst, std::vector<PrimitiveGeometry>& out) {
  const tinygltf::Node& node = ctx.model.nodes[static_cast<std::size_t>(inst.node)];
  if (node.skin >= 0)
    ctx.report.warnings.push_back("node " + std::to_string(inst.node) + ": skin ignored (bind pose loaded)");
  if (node.mesh < 0) return;
  const tinygltf::Mesh& mesh = checkedMesh(ctx, node.mesh, inst.node);
  // One movable SceneNode per node instance with a mesh (UpdateScene names it by the glTF node name).
  const auto record = static_cast<std::uint32_t>(ctx.scene.nodes.size());
  SceneNode movable;
  movable.name = node.name.empty() ? "node" + std::to_string(inst.node) : node.name;
  if (!ctx.nodeNames.insert(movable.name).second) {  // a repeated name gets its node index
    movable.name += "#" + std::to_string(inst.node);
    ctx.nodeNames.insert(movable.name);
  }
  movable.world = inst.world;
  movable.mesh = node.mesh;
  ctx.scene.nodes.push_back(std::move(movable));
  for (std::size_t p = 0; p < mesh.primitives.size(); ++p) {
    const tinygltf::Primitive& prim = mesh.primitives[p];
    if (!isTriangleMode(prim.mode)) {
      ++ctx.report.skippedPrimitives;  // POINTS, LINES, LINE_LOOP, LINE_STRIP: nothing to ray trace
      continue;
    }
    out.push_back(readPrimitive(ctx, prim, inst.world, primitiveName(node.mesh, p)));
    out.back().node = record;
    ++ctx.report.primitives;
  }
}

}  // namespace

Scene loadGltf(const std::string& path, SceneLoadReport* report) { return loadGltf(readSceneSource(path), report); }

Scene loadGltf(const SceneSource& source, SceneLoadReport* reportOut, const SceneLimits& limits) {
  SceneLoadReport local;
  SceneLoadReport& report = reportOut ? *reportOut : local;
  report = SceneLoadReport{};
  const std::string& path = source.name;

  GltfDocument doc = readGltfDocument(source, limits);
  report.warnings = std::move(doc.warnings);
  Scene scene;
  scene.name = path;
  appendGltfMaterials(doc.model, scene, path, report);

  LoadContext ctx{doc.model, path, report, scene, limits};
  const std::vector<NodeInstance> instances = flattenSceneNodes(doc.model, path);
  checkSizeBudget(ctx, instances);
  std::vector<PrimitiveGeometry> prims;
  for (const NodeInstance& inst : instances) {
    readNodeMeshes(ctx, inst, prims);
    appendNodeLight(doc.model, inst, scene, path);
  }
  appendGeometry(scene, prims, report);
  if (report.skippedPrimitives > 0)
    report.warnings.push_back(std::to_string(report.skippedPrimitives) + " point/line primitives skipped");
  if (scene.triangles.empty())
    throw SceneError(path,
                     "the scene has no triangles (nothing to render; check that the default scene contains "
                     "meshes with triangle primitives)");
  if (scene.materials.empty()) scene.materials.push_back(Material{"default"});
  if (const std::size_t unmarked = markConvexNodes(scene)) {
    report.warnings.push_back(std::to_string(unmarked) +
                              " nodes were not tested for convexity (the load's budget of plane tests is spent); rays "
                              "that leave them walk them (docs/BVH.md §9.6)");
  }

  report.triangles = scene.triangles.size();
  report.vertices = scene.positions.size();
  report.textures = scene.textures.size();
  report.lights = scene.lights.size();
  return scene;
}

}  // namespace ht
