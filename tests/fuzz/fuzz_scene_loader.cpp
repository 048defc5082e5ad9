// fuzz_scene_loader.cpp - libFuzzer target: ht::loadScene on .gltf, .glb, .obj and .off files.
//
// The daemon stores uploaded bytes as a file and calls loadScene(path) (server/scene_rpcs.cpp, scene_library.cpp),
// and the glTF loader only has a path API, so the fuzzer does the same: it writes the input to a file in a private
// folder and loads it. The extension comes from the content so that real files are valid seeds unchanged:
// "glTF" magic -> .glb, first non-blank '{' -> .gltf, "OFF"/"COFF"/"NOFF"/"CNOFF" start -> .off, else .obj.
// The only acceptable failure is an ht::SceneError.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>
#include <system_error>

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

// One folder per process (libFuzzer -fork/-jobs run several), removed at exit.
struct PrivateDir {
  std::filesystem::path path =
      std::filesystem::temp_directory_path() / ("holotrace-fuzz-scene-" + std::to_string(::getpid()));
  PrivateDir() { std::filesystem::create_directories(path); }
  ~PrivateDir() {
    std::error_code ignored;
    std::filesystem::remove_all(path, ignored);
  }
};

const std::filesystem::path& privateDir() {
  static const PrivateDir dir;
  return dir.path;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  const std::filesystem::path file = privateDir() / ("input" + extensionFor(bytes));
  {
    std::ofstream out(file, std::ios::binary | std::ios::trunc);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  }
  try {
    (void)ht::loadScene(file.string());
  } catch (const ht::SceneError&) {}
  std::filesystem::remove(file);
  return 0;
}
