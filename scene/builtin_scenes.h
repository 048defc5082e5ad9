// builtin_scenes.h - procedural scenes addressed as "builtin:NAME" (see builtinSceneNames() in scene.h).
//
// World units ~1, framed for a portrait 3:4 Looking Glass: content fits x in [-0.75, 0.75], y in [-1, 1]
// around the focal plane, and every scene's bounds centre is the origin so that a focal plane placed at
// the bounds centre is z = 0 with objects both in front of (+z, toward the viewer) and behind it. The
// camera looks down -z from +z.
#pragma once
#include <string_view>

#include "scene/scene.h"

namespace ht {

// `name` without the "builtin:" prefix ("showcase", "plain", "sphere", "mirror-test"). Throws SceneError
// naming "builtin:<name>" and listing the available scenes when the name is unknown.
Scene makeBuiltinScene(std::string_view name);

// Ground, mirror sphere, glass sphere, diffuse box + sphere, emissive sphere, checker-textured floor,
// a point and a directional light: every SceneFeatures flag is set.
Scene makeShowcaseScene();
// Diffuse objects only (no lights, mirrors, glass, textures or emission): shaded by ambient light.
Scene makePlainScene();
// One diffuse icosphere (5 subdivisions, 20480 triangles), radius 1, centred at the origin.
Scene makeSphereScene();
// A 45-degree mirror and an emissive sphere that a +z camera sees only in the mirror (geometry in the .cpp).
Scene makeMirrorTestScene();

}  // namespace ht
