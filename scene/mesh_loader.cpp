// mesh_loader.cpp - OBJ and OFF parsing with std::from_chars (no locale, no iostreams: the 69,666-triangle
// bunny parses in a few milliseconds).
#include "scene/mesh_loader.h"

#include <charconv>
#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

#include "common/error.h"
#include "scene/file_bytes.h"
#include "scene/scene_limits.h"

namespace ht {
namespace {

// A cursor over one line of text.
struct LineCursor {
  const char* p;
  const char* end;

  void skipSpace() {
    while (p < end && (*p == ' ' || *p == '\t' || *p == '\r')) ++p;
  }
  bool atEnd() {
    skipSpace();
    return p >= end || *p == '#';
  }
  std::string_view word() {
    skipSpace();
    const char* b = p;
    while (p < end && *p != ' ' && *p != '\t' && *p != '\r') ++p;
    return {b, static_cast<std::size_t>(p - b)};
  }
  bool number(float& out) {
    skipSpace();
    if (p < end && *p == '+') ++p;
    const auto r = std::from_chars(p, end, out);
    if (r.ec != std::errc() && r.ec != std::errc::result_out_of_range) return false;
    p = r.ptr;
    return true;
  }
  bool integer(long long& out) {
    skipSpace();
    if (p < end && *p == '+') ++p;
    const auto r = std::from_chars(p, end, out);
    if (r.ec != std::errc()) return false;
    p = r.ptr;
    return true;
  }
};

// Splits text into lines; calls f(lineNumber, cursor) for each.
template <class F>
void forEachLine(std::string_view text, F&& f) {
  const char* p = text.data();
  const char* end = p + text.size();
  std::size_t lineNumber = 0;
  while (p < end) {
    const char* eol = p;
    while (eol < end && *eol != '\n') ++eol;
    ++lineNumber;
    LineCursor line{p, eol};
    if (!f(lineNumber, line)) return;
    p = eol + 1;
  }
}

std::string at(std::size_t lineNumber) { return "line " + std::to_string(lineNumber) + ": "; }

Scene emptyMeshScene(const std::string& file) {
  Scene scene;
  scene.name = file;
  Material m;
  m.name = "default";
  scene.materials.push_back(m);
  return scene;
}

void countNonFinite(const Scene& scene, SceneLoadReport* report) {
  if (!report) return;
  for (const glm::vec3& v : scene.positions)
    if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z)) ++report->nonFiniteVertices;
  report->triangles = scene.triangles.size();
  report->vertices = scene.positions.size();
  report->primitives = 1;
}

// Fan triangulation (v0, vi, vi+1) of one polygon; appends to the scene with material 0.
void appendFan(Scene& scene, const std::vector<std::uint32_t>& polygon, const std::string& file, std::size_t line) {
  if (scene.triangles.size() + polygon.size() - 2 > limits::kMaxTriangles)
    throw SceneError(
        file, at(line) + "more than " + std::to_string(limits::kMaxTriangles) + " triangles (simplify the mesh)");
  for (std::size_t i = 1; i + 1 < polygon.size(); ++i) {
    scene.triangles.push_back({polygon[0], polygon[i], polygon[i + 1]});
    scene.triangleMaterial.push_back(0);
  }
}

// ---- OBJ -------------------------------------------------------------------------------------------------

// One face vertex reference "v", "v/vt", "v//vn" or "v/vt/vn": returns the 0-based position index.
// Negative indices count back from the last vertex defined so far (Wavefront OBJ spec, "Referencing vertex
// data": -1 is the most recent vertex).
std::uint32_t objVertexRef(std::string_view token, std::size_t definedVertices, const std::string& file,
                           std::size_t line) {
  long long index = 0;
  const char* b = token.data();
  const char* e = b + token.size();
  if (b < e && *b == '+') ++b;
  const auto r = std::from_chars(b, e, index);
  if (r.ec != std::errc() || (r.ptr != e && *r.ptr != '/'))
    throw SceneError(file,
                     at(line) + "bad face vertex '" + std::string(token) + "' (expected v, v/vt, v//vn or v/vt/vn)");
  const long long resolved = index > 0 ? index - 1 : static_cast<long long>(definedVertices) + index;
  if (index == 0 || resolved < 0 || resolved >= static_cast<long long>(definedVertices))
    throw SceneError(file, at(line) + "face vertex " + std::to_string(index) + " does not refer to one of the " +
                               std::to_string(definedVertices) + " vertices defined so far (indices are 1-based; " +
                               "negative ones count back from the last vertex)");
  return static_cast<std::uint32_t>(resolved);
}

void parseObjVertex(Scene& scene, LineCursor& line, const std::string& file, std::size_t lineNumber) {
  glm::vec3 p;
  if (!line.number(p.x) || !line.number(p.y) || !line.number(p.z))
    throw SceneError(file, at(lineNumber) + "vertex needs three numbers 'v x y z'");
  scene.positions.push_back(p);
}

void parseObjFace(Scene& scene, LineCursor& line, std::vector<std::uint32_t>& polygon, const std::string& file,
                  std::size_t lineNumber) {
  polygon.clear();
  while (!line.atEnd()) polygon.push_back(objVertexRef(line.word(), scene.positions.size(), file, lineNumber));
  if (polygon.size() < 3)
    throw SceneError(file,
                     at(lineNumber) + "face has " + std::to_string(polygon.size()) + " vertices (need at least 3)");
  appendFan(scene, polygon, file, lineNumber);
}

// ---- OFF -------------------------------------------------------------------------------------------------

struct OffHeader {
  std::size_t vertices = 0, faces = 0;
};

// Header keyword: [ST][C][N][4][n]OFF. Only 3D variants are accepted; colour/normal/texcoord prefixes just
// add per-vertex values we skip (Geomview OFF file format documentation).
bool isSupportedOffKeyword(std::string_view w) {
  if (w.size() < 3 || w.substr(w.size() - 3) != "OFF") return false;
  for (char c : w.substr(0, w.size() - 3))
    if (c != 'S' && c != 'T' && c != 'C' && c != 'N') return false;
  return true;
}

// Line-by-line OFF reader: header keyword, counts, vertex lines, face lines, one stage at a time.
struct OffParser {
  enum class Stage { Keyword, Counts, Vertices, Faces, Done };
  std::string_view text;
  const std::string& file;
  Scene scene;
  Stage stage = Stage::Keyword;
  OffHeader header;
  std::size_t facesRead = 0;
  std::vector<std::uint32_t> polygon;

  // Returns false once every declared face is read (trailing content is ignored).
  bool line(std::size_t lineNumber, LineCursor& line) {
    if (line.atEnd()) return true;
    switch (stage) {
      case Stage::Keyword:
        keyword(lineNumber, line);
        if (!line.atEnd()) counts(lineNumber, line);  // "OFF 8 6 0" on one line
        return true;
      case Stage::Counts: counts(lineNumber, line); return true;
      case Stage::Vertices: vertex(lineNumber, line); return true;
      case Stage::Faces: face(lineNumber, line); return true;
      case Stage::Done: return false;
    }
    return false;
  }

  void keyword(std::size_t lineNumber, LineCursor& line) {
    const std::string_view word = line.word();
    if (!isSupportedOffKeyword(word))
      throw SceneError(file, at(lineNumber) + "expected the header 'OFF' (or COFF/NOFF/CNOFF), found '" +
                                 std::string(word) + "' (4D and nOFF variants are not supported)");
    stage = Stage::Counts;
  }

  void counts(std::size_t lineNumber, LineCursor& line) {
    long long nv = 0, nf = 0;
    if (!line.integer(nv) || !line.integer(nf) || nv < 0 || nf < 0)
      throw SceneError(file, at(lineNumber) + "expected 'nVertices nFaces nEdges' after the OFF header");
    // A vertex line needs at least 6 bytes ("0 0 0\n") and a face line 8: refuse counts the file cannot
    // hold before reserving memory for them.
    if (static_cast<unsigned long long>(nv) > text.size() / 6 || static_cast<unsigned long long>(nf) > text.size() / 8)
      throw SceneError(file, at(lineNumber) + "declares " + std::to_string(nv) + " vertices and " + std::to_string(nf) +
                                 " faces, more than a " + std::to_string(text.size()) +
                                 "-byte file can hold (the header counts are wrong or the file is truncated)");
    header = {static_cast<std::size_t>(nv), static_cast<std::size_t>(nf)};
    scene.positions.reserve(header.vertices);
    stage = header.vertices > 0 ? Stage::Vertices : header.faces > 0 ? Stage::Faces : Stage::Done;
  }

  void vertex(std::size_t lineNumber, LineCursor& line) {
    glm::vec3 p;
    if (!line.number(p.x) || !line.number(p.y) || !line.number(p.z))
      throw SceneError(file, at(lineNumber) + "vertex needs three numbers 'x y z'");
    scene.positions.push_back(p);
    if (scene.positions.size() == header.vertices) stage = header.faces > 0 ? Stage::Faces : Stage::Done;
  }

  void face(std::size_t lineNumber, LineCursor& line) {
    long long n = 0;
    if (!line.integer(n) || n < 3 || static_cast<unsigned long long>(n) > text.size())
      throw SceneError(file, at(lineNumber) + "face must start with its vertex count (>= 3)");
    polygon.clear();
    for (long long k = 0; k < n; ++k) {
      long long index = 0;
      if (!line.integer(index))
        throw SceneError(file, at(lineNumber) + "face lists fewer than its " + std::to_string(n) + " vertex indices");
      if (index < 0 || static_cast<std::size_t>(index) >= header.vertices)
        throw SceneError(file, at(lineNumber) + "vertex index " + std::to_string(index) + " out of range [0, " +
                                   std::to_string(header.vertices) + ") (OFF indices are 0-based)");
      polygon.push_back(static_cast<std::uint32_t>(index));
    }
    appendFan(scene, polygon, file, lineNumber);
    if (++facesRead == header.faces) stage = Stage::Done;
  }
};

}  // namespace

Scene parseObj(std::string_view text, const std::string& file, SceneLoadReport* report) {
  Scene scene = emptyMeshScene(file);
  std::vector<std::uint32_t> polygon;
  forEachLine(text, [&](std::size_t lineNumber, LineCursor& line) {
    if (line.atEnd()) return true;
    const std::string_view keyword = line.word();
    if (keyword == "v")
      parseObjVertex(scene, line, file, lineNumber);
    else if (keyword == "f")
      parseObjFace(scene, line, polygon, file, lineNumber);
    // vt, vn, usemtl, mtllib, o, g, s, l, p and unknown statements: not needed for positions-only meshes.
    return true;
  });
  if (scene.triangles.empty()) throw SceneError(file, "no faces found (an OBJ mesh needs 'f' lines)");
  countNonFinite(scene, report);
  return scene;
}

Scene parseOff(std::string_view text, const std::string& file, SceneLoadReport* report) {
  OffParser parser{text, file, emptyMeshScene(file)};
  forEachLine(text, [&](std::size_t lineNumber, LineCursor& line) { return parser.line(lineNumber, line); });
  if (parser.stage != OffParser::Stage::Done)
    throw SceneError(file, "file ends before all vertices and faces declared in the header were read (truncated?)");
  if (parser.scene.triangles.empty()) throw SceneError(file, "no faces found");
  countNonFinite(parser.scene, report);
  return std::move(parser.scene);
}

Scene loadObj(const std::string& path, SceneLoadReport* report) { return parseObj(readSceneFile(path), path, report); }

Scene loadOff(const std::string& path, SceneLoadReport* report) { return parseOff(readSceneFile(path), path, report); }

}  // namespace ht
