// builtin_scenes.cpp - the procedural scenes behind "builtin:NAME".
#include "scene/builtin_scenes.h"

#include <string>

#include "common/error.h"
#include "scene/convex_sides.h"
#include "scene/mesh_generators.h"

namespace ht {
namespace {

Material diffuse(std::string name, glm::vec3 color) {
  Material m;
  m.name = std::move(name);
  m.baseColor = color;
  return m;
}

Material mirror(std::string name) {
  Material m = diffuse(std::move(name), glm::vec3(0.95f));
  m.metallic = 1.0f;
  m.roughness = 0.0f;
  return m;
}

Material glass(std::string name, float ior) {
  Material m = diffuse(std::move(name), glm::vec3(1.0f));
  m.roughness = 0.0f;
  m.transmission = 1.0f;
  m.ior = ior;
  return m;
}

Material emitter(std::string name, glm::vec3 radiance) {
  Material m = diffuse(std::move(name), glm::vec3(0.0f));
  m.emissive = radiance;
  return m;
}

// Floor y = -0.8 (x in [-1, 1], z in [-1, 1]) and back wall z = -1 (y in [-0.8, 0.8]): the bounds span
// y in [-0.8, 0.8] and z in [-1, 1], both centred on 0.
void addRoom(Scene& scene, std::uint32_t floorMaterial, std::uint32_t wallMaterial) {
  makeQuad(scene, {0.0f, -0.8f, 0.0f}, {0.0f, 0.0f, 1.0f}, {1.0f, 0.0f, 0.0f}, floorMaterial);  // faces +y
  makeQuad(scene, {0.0f, 0.0f, -1.0f}, {1.0f, 0.0f, 0.0f}, {0.0f, 0.8f, 0.0f}, wallMaterial);   // faces +z
}

// Appends what `add` generates as the movable node `name` (holotraced UpdateScene moves it by name). `convex`: the
// sides outside it (SceneNode::convexSides), known by construction -- generated spheres and boxes are convex with
// their winding outwards, the room's floor and back wall meet in an inner corner -- so a built-in scene does not pay
// for convexSides' plane tests at every load (ConvexSides.BuiltinMarksAreWhatTheTestFinds checks them).
template <class Add>
void addNode(Scene& scene, std::string name, std::uint8_t convex, Add add) {
  SceneNode node;
  node.name = std::move(name);
  node.convexSides = convex;
  node.firstVertex = static_cast<std::uint32_t>(scene.positions.size());
  node.firstTriangle = static_cast<std::uint32_t>(scene.triangles.size());
  add();
  node.vertexCount = static_cast<std::uint32_t>(scene.positions.size()) - node.firstVertex;
  node.triangleCount = static_cast<std::uint32_t>(scene.triangles.size()) - node.firstTriangle;
  scene.nodes.push_back(std::move(node));
}

constexpr int kSphereSubdivisions = 4;  // 5120 triangles per sphere: smooth silhouettes at panel resolution

}  // namespace

Scene makeShowcaseScene() {
  Scene s;
  s.name = "builtin:showcase";
  const int checker = addCheckerTexture(s, "floor-checker", 256, 8, glm::vec3(0.85f), glm::vec3(0.25f, 0.3f, 0.45f));
  Material floor = diffuse("floor", glm::vec3(1.0f));
  floor.baseColorTexture = checker;
  const std::uint32_t floorMat = addMaterial(s, floor);
  const std::uint32_t wallMat = addMaterial(s, diffuse("wall", {0.7f, 0.72f, 0.75f}));
  addNode(s, "room", kConvexBack, [&] { addRoom(s, floorMat, wallMat); });

  // Behind the focal plane (z < 0): a mirror sphere, and a red box carrying a green sphere.
  addNode(s, "mirror-sphere", kConvexFront, [&] {
    makeIcosphere(s, {-0.35f, -0.35f, -0.45f}, 0.45f, kSphereSubdivisions, addMaterial(s, mirror("mirror")));
  });
  addNode(s, "red-box", kConvexFront, [&] {
    makeBox(s, {0.38f, -0.55f, -0.5f}, glm::vec3(0.25f), addMaterial(s, diffuse("red", {0.8f, 0.12f, 0.1f})));
  });
  addNode(s, "green-sphere", kConvexFront, [&] {
    makeIcosphere(s, {0.38f, -0.05f, -0.5f}, 0.25f, kSphereSubdivisions,
                  addMaterial(s, diffuse("green", {0.15f, 0.7f, 0.2f})));
  });
  // In front of it (z > 0): a glass sphere and a small glowing sphere.
  addNode(s, "glass-sphere", kConvexFront, [&] {
    makeIcosphere(s, {0.28f, -0.45f, 0.45f}, 0.35f, kSphereSubdivisions, addMaterial(s, glass("glass", 1.5f)));
  });
  addNode(s, "glow-sphere", kConvexFront, [&] {
    makeIcosphere(s, {-0.38f, -0.65f, 0.55f}, 0.15f, kSphereSubdivisions,
                  addMaterial(s, emitter("glow", {3.0f, 1.8f, 0.5f})));
  });

  Light point;  // above and in front, so shadows fall onto the floor and the back wall
  point.type = Light::Type::Point;
  point.position = {0.6f, 1.4f, 1.2f};
  point.color = {1.0f, 0.95f, 0.85f};
  point.intensity = 6.0f;  // candela
  s.lights.push_back(point);

  Light sun;
  sun.type = Light::Type::Directional;
  sun.direction = glm::normalize(glm::vec3(-0.35f, -1.0f, -0.45f));  // travels down, left and away from the viewer
  sun.color = {0.8f, 0.85f, 1.0f};
  sun.intensity = 0.8f;  // lux
  s.lights.push_back(sun);
  return s;
}

Scene makePlainScene() {
  Scene s;
  s.name = "builtin:plain";
  addNode(s, "room", kConvexBack, [&] {
    addRoom(s, addMaterial(s, diffuse("floor", {0.6f, 0.6f, 0.55f})),
            addMaterial(s, diffuse("wall", {0.45f, 0.5f, 0.6f})));
  });
  addNode(s, "orange-sphere", kConvexFront, [&] {
    makeIcosphere(s, {-0.3f, -0.4f, -0.45f}, 0.4f, kSphereSubdivisions,
                  addMaterial(s, diffuse("orange", {0.9f, 0.45f, 0.1f})));
  });
  addNode(s, "teal-box", kConvexFront, [&] {
    makeBox(s, {0.38f, -0.55f, -0.4f}, glm::vec3(0.25f), addMaterial(s, diffuse("teal", {0.1f, 0.6f, 0.6f})));
  });
  addNode(s, "violet-sphere", kConvexFront, [&] {
    makeIcosphere(s, {0.25f, -0.5f, 0.5f}, 0.3f, kSphereSubdivisions,
                  addMaterial(s, diffuse("violet", {0.55f, 0.3f, 0.8f})));
  });
  addNode(s, "yellow-box", kConvexFront, [&] {
    makeBox(s, {-0.35f, -0.65f, 0.6f}, glm::vec3(0.15f), addMaterial(s, diffuse("yellow", {0.9f, 0.85f, 0.2f})));
  });
  return s;
}

Scene makeSphereScene() {
  Scene s;
  s.name = "builtin:sphere";
  addNode(s, "sphere", kConvexFront,
          [&] { makeIcosphere(s, glm::vec3(0.0f), 1.0f, 5, addMaterial(s, diffuse("sphere", glm::vec3(0.8f)))); });
  return s;
}

// Geometry of builtin:mirror-test (camera on the +z axis at distance D >= ~4, looking down -z, vertical
// half-field at z = 0 below 1.75 units, e.g. the Looking Glass default targetDiam 2 -> half-field 1):
//   * mirror: the square plane y + z = 0 (unit normal (0, 1, 1)/sqrt 2, facing the camera and up),
//     x in [-1, 1], y in [-3.25, 3.25] (z = -y). A primary ray (x0, y0, D) + t (0, 0, -1) hits it at
//     (x0, y0, -y0) and reflects (r = d - 2 (d.n) n) into the direction (0, 1, 0);
//   * emitter: a sphere of radius 0.75 at (0, 2.5, 0), above the view frustum (its lowest point y = 1.75
//     is outside the half-field), so it is invisible directly. Reflected rays from (x0, y0, -y0) going +y
//     hit it iff x0^2 + y0^2 < 0.75^2: the mirror shows a disc of radius 0.75 (focal-plane units) at the
//     image centre in the emitter's colour; everything else shows the background.
//   * bounds: x [-1, 1], y [-3.25, 3.25], z [-3.25, 3.25]: centred on the origin.
Scene makeMirrorTestScene() {
  Scene s;
  s.name = "builtin:mirror-test";
  addNode(s, "mirror", kConvexFront | kConvexBack, [&] {
    makeQuad(s, glm::vec3(0.0f), {1.0f, 0.0f, 0.0f}, {0.0f, 3.25f, -3.25f}, addMaterial(s, mirror("mirror")));
  });
  addNode(s, "emitter", kConvexFront, [&] {
    makeIcosphere(s, {0.0f, 2.5f, 0.0f}, 0.75f, kSphereSubdivisions,
                  addMaterial(s, emitter("magenta", {1.0f, 0.1f, 0.8f})));
  });
  return s;
}

Scene makeBuiltinScene(std::string_view name) {
  if (name == "showcase") return makeShowcaseScene();
  if (name == "plain") return makePlainScene();
  if (name == "sphere") return makeSphereScene();
  if (name == "mirror-test") return makeMirrorTestScene();
  std::string available;
  for (const std::string& n : builtinSceneNames()) available += (available.empty() ? "" : ", ") + n;
  throw SceneError("builtin:" + std::string(name), "unknown built-in scene (available: " + available + ")");
}

std::vector<std::string> builtinSceneNames() {
  return {"builtin:showcase", "builtin:plain", "builtin:sphere", "builtin:mirror-test"};
}

}  // namespace ht
