// fuzz_scene_loader.cpp - libFuzzer target: ht::loadScene on .gltf, .glb, .obj and .off files.
//
// The daemon loads uploaded bytes from memory as a SceneSource (scene/scene_source.h; server/scene_rpcs.cpp), and so
// does the fuzzer: no file, no external URIs (a .gltf's external files are reported missing). The extension comes
// from the content so that real files are valid seeds unchanged:
// "glTF" magic -> .glb, first non-blank '{' -> .gltf, "OFF"/"COFF"/"NOFF"/"CNOFF" start -> .off, else .obj.
// The only acceptable failure is an ht::SceneError.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "common/error.h"
#include "scene/load_scene.h"

namespace {

std::string extensionFor(std::string_view bytes) {
  if (bytes.substr(0, 4) == "glTF") return ".glb";
  const std::size_t first = bytes.find_first_not_of(" \t\r\n");
  if (first != std::string_view::npos && bytes[first] == '{') return ".gltf";
  for (std::string_view header : {"OFF", "COFF", "NOFF", "CNOFF"})
    if (bytes.substr(0, header.size()) == header) return ".off";
  return ".obj";
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  const ht::SceneSource source{"input" + extensionFor(bytes), std::string(bytes), {}, {}};
  try {
    (void)ht::loadScene(source);
  } catch (const ht::SceneError&) {}
  return 0;
}
