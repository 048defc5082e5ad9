// scene_bytes.cpp - see scene_bytes.h.
#include "cluster/scene_bytes.h"

#include <cstring>
#include <string>
#include <type_traits>

#include "cluster/cluster_error.h"

namespace ht::cluster {
namespace {

// A field added to these types must be added to put()/take() below too: the sizes fail to compile until it is.
static_assert(sizeof(Light) == 56 && sizeof(SceneNode) == 184 && sizeof(Texture) == 64 && sizeof(Material) == 80 &&
                  sizeof(Scene) == 272,
              "Scene changed: update cluster/scene_bytes.cpp (encode and decode every field), then these sizes");

class Writer {
 public:
  template <typename T>
  void raw(const T& value) {
    static_assert(std::is_trivially_copyable_v<T>);
    const auto* p = reinterpret_cast<const std::uint8_t*>(&value);
    bytes_.insert(bytes_.end(), p, p + sizeof(T));
  }
  template <typename T>
  void array(const std::vector<T>& values) {
    static_assert(std::is_trivially_copyable_v<T>);
    raw(static_cast<std::uint64_t>(values.size()));
    const auto* p = reinterpret_cast<const std::uint8_t*>(values.data());
    bytes_.insert(bytes_.end(), p, p + values.size() * sizeof(T));
  }
  void text(const std::string& value) { array(std::vector<char>(value.begin(), value.end())); }
  std::vector<std::uint8_t> take() { return std::move(bytes_); }

 private:
  std::vector<std::uint8_t> bytes_;
};

class Reader {
 public:
  explicit Reader(std::span<const std::uint8_t> bytes) : bytes_(bytes) {}
  template <typename T>
  void raw(T& value) {
    need(sizeof(T), "a field");
    std::memcpy(&value, bytes_.data() + at_, sizeof(T));
    at_ += sizeof(T);
  }
  template <typename T>
  void array(std::vector<T>& values) {
    std::uint64_t count = 0;
    raw(count);
    if (count > (bytes_.size() - at_) / sizeof(T)) fail("an array of " + std::to_string(count) + " elements");
    values.resize(static_cast<std::size_t>(count));
    std::memcpy(values.data(), bytes_.data() + at_, values.size() * sizeof(T));
    at_ += values.size() * sizeof(T);
  }
  void text(std::string& value) {
    std::vector<char> chars;
    array(chars);
    value.assign(chars.begin(), chars.end());
  }
  void finish() const {
    if (at_ != bytes_.size()) fail(std::to_string(bytes_.size() - at_) + " bytes after the scene");
  }

 private:
  void need(std::size_t n, const char* what) const {
    if (n > bytes_.size() - at_) fail(what);
  }
  [[noreturn]] void fail(const std::string& what) const {
    throw ClusterError("scene bytes from rank 0 are damaged at byte " + std::to_string(at_) + " of " +
                       std::to_string(bytes_.size()) + ": " + what + " does not fit (ranks must run the same build)");
  }
  std::span<const std::uint8_t> bytes_;
  std::size_t at_ = 0;
};

// One function per type serves both directions: `io` is a Writer (const objects) or a Reader.
template <typename Io, typename M>
void material(Io& io, M& m) {
  io.text(m.name);
  io.raw(m.baseColor);
  io.raw(m.baseColorTexture);
  io.raw(m.emissive);
  io.raw(m.metallic);
  io.raw(m.roughness);
  io.raw(m.transmission);
  io.raw(m.ior);
}

template <typename Io, typename T>
void texture(Io& io, T& t) {
  io.text(t.name);
  io.raw(t.width);
  io.raw(t.height);
  io.array(t.texels);
}

template <typename Io, typename L>
void light(Io& io, L& l) {
  io.raw(l.type);
  io.raw(l.position);
  io.raw(l.direction);
  io.raw(l.color);
  io.raw(l.intensity);
  io.raw(l.range);
  io.raw(l.innerConeAngle);
  io.raw(l.outerConeAngle);
}

template <typename Io, typename N>
void node(Io& io, N& n) {
  io.text(n.name);
  io.raw(n.firstVertex);
  io.raw(n.vertexCount);
  io.raw(n.firstTriangle);
  io.raw(n.triangleCount);
  io.raw(n.world);
  io.raw(n.mesh);
}

template <typename Io, typename S>
void scalars(Io& io, S& s) {
  io.text(s.name);
  io.array(s.positions);
  io.array(s.normals);
  io.array(s.texcoords);
  io.array(s.triangles);
  io.array(s.triangleMaterial);
  io.raw(s.background);
  io.raw(s.ambient);
}

}  // namespace

std::vector<std::uint8_t> encodeScene(const Scene& scene) {
  Writer w;
  scalars(w, scene);
  w.raw(static_cast<std::uint64_t>(scene.materials.size()));
  for (const Material& m : scene.materials) material(w, m);
  w.raw(static_cast<std::uint64_t>(scene.textures.size()));
  for (const Texture& t : scene.textures) texture(w, t);
  w.raw(static_cast<std::uint64_t>(scene.lights.size()));
  for (const Light& l : scene.lights) light(w, l);
  w.raw(static_cast<std::uint64_t>(scene.nodes.size()));
  for (const SceneNode& n : scene.nodes) node(w, n);
  return w.take();
}

Scene decodeScene(std::span<const std::uint8_t> bytes) {
  Reader r(bytes);
  Scene scene;
  scalars(r, scene);
  // Each element takes at least one byte, so a count is bounded by the bytes left before anything is allocated.
  const auto count = [&](auto& values) {
    std::uint64_t n = 0;
    r.raw(n);
    if (n > bytes.size()) throw ClusterError("scene bytes from rank 0 are damaged: a count of " + std::to_string(n));
    values.resize(static_cast<std::size_t>(n));
  };
  count(scene.materials);
  for (Material& m : scene.materials) material(r, m);
  count(scene.textures);
  for (Texture& t : scene.textures) texture(r, t);
  count(scene.lights);
  for (Light& l : scene.lights) light(r, l);
  count(scene.nodes);
  for (SceneNode& n : scene.nodes) node(r, n);
  r.finish();
  return scene;
}

}  // namespace ht::cluster
