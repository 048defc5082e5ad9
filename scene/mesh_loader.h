// mesh_loader.h - Wavefront OBJ and OFF triangle meshes (positions only), e.g. the glmark2 bunny and the
// CGAL .off meshes of docs/TOOLCHAIN.md §7.
//
// The result has world = file coordinates, one default diffuse material, no normals (renderers use face
// normals) and no texcoords. Polygons are fan-triangulated (v0, vi, vi+1). Failures throw SceneError naming
// the file and the line.
#pragma once
#include <string>
#include <string_view>

#include "scene/load_report.h"
#include "scene/scene.h"

namespace ht {

// OBJ: `v x y z [w]`, `f` with `v`, `v/vt`, `v//vn`, `v/vt/vn` vertex references (1-based, negative =
// relative to the vertices defined so far). vt/vn data, materials (usemtl/mtllib), groups, smoothing
// groups, lines and points are ignored.
Scene loadObj(const std::string& path, SceneLoadReport* report = nullptr);
Scene parseObj(std::string_view text, const std::string& file, SceneLoadReport* report = nullptr);

// OFF (Geomview / CGAL): header `OFF` (also COFF, NOFF, CNOFF: extra per-vertex values are ignored), counts
// `nVertices nFaces nEdges`, vertices, then faces `n i0 ... i(n-1) [colour]` with 0-based indices.
Scene loadOff(const std::string& path, SceneLoadReport* report = nullptr);
Scene parseOff(std::string_view text, const std::string& file, SceneLoadReport* report = nullptr);

}  // namespace ht
