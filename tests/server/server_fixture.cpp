// server_fixture.cpp - see server_fixture.h.
#include "tests/server/server_fixture.h"

#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cstring>
#include <fstream>
#include <iterator>

namespace ht::server::test {

TempDir::TempDir() {
  static std::atomic<int> counter{0};
  path = std::filesystem::temp_directory_path() /
         ("ht-server-test-" + std::to_string(::getpid()) + "-" + std::to_string(counter++));
  std::filesystem::remove_all(path);
  std::filesystem::create_directories(path);
}

TempDir::~TempDir() {
  std::error_code ec;
  std::filesystem::remove_all(path, ec);
}

std::string tinyDisplayJson() {
  return R"({
  "name": "tiny",
  "description": "96x64 lenticular test panel",
  "model": "lenticular",
  "calibration": {
    "configVersion": "3.0", "serial": "LKG-TEST-1", "pitch": 52.59, "slope": -7.21, "center": 0.40,
    "viewCone": 40, "invView": 1, "verticalAngle": 0, "DPI": 324, "screenW": 96, "screenH": 64,
    "flipImageX": 0, "flipImageY": 0, "flipSubp": 0, "CellPatternMode": 0, "subpixelCells": []
  },
  "camera": { "target": "auto", "size": "auto", "fovyDeg": 14, "depthiness": 1.0 },
  "spp": 1
}
)";
}

std::string cubeObj() {
  return "v -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\nv -1 -1 1\nv 1 -1 1\nv 1 1 1\nv -1 1 1\n"
         "f 1 3 2\nf 1 4 3\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\nf 4 8 7\nf 4 7 3\nf 1 5 8\nf 1 8 4\n"
         "f 2 3 7\nf 2 7 6\n";
}

void writeText(const std::filesystem::path& file, const std::string& text) {
  std::filesystem::create_directories(file.parent_path());
  std::ofstream(file, std::ios::binary) << text;
}

DaemonFiles::DaemonFiles() {
  writeText(dir.path / "displays" / "tiny.json", tinyDisplayJson());
  // Multi-view displays: a 3x2 capture grid (its views form a quilt) and a 3-projector HPO array (they do not).
  writeText(dir.path / "displays" / "rig.json", R"({"name": "rig", "model": "capture-grid", "spp": 1,
    "captureGrid": {"columns": 3, "rows": 2, "spacing": [0.1, 0.1], "distance": 3, "window": {"width": 2.4,
    "height": 1.8}, "image": {"width": 24, "height": 16}}})");
  writeText(dir.path / "displays" / "wall.json", R"({"name": "wall", "model": "projector-array", "spp": 1,
    "projectorArray": {"screen": {"width": 160, "height": 90}, "observerDistance": 300, "observerHeight": 0,
    "angularScattering": "auto", "image": {"width": 20, "height": 12},
    "projectors": [{"position": [-10, 0, -180]}, {"position": [0, 0, -180]}, {"position": [10, 0, -180]}]}})");
  writeText(sceneRoot() / "cube.obj", cubeObj());
  writeText(dir.path / "secret.obj", cubeObj());  // outside the scene root
  std::filesystem::create_directories(outputRoot());
}

std::string DaemonFiles::socketAddress() const { return "unix:" + (dir.path / "run" / "holotraced.sock").string(); }

DaemonConfig DaemonFiles::config() const {
  DaemonConfig c;
  c.displaysDir = dir.path / "displays";
  c.sceneRoot = sceneRoot();
  c.outputRoot = outputRoot();
  c.workDir = dir.path / "work";
  c.listen = {socketAddress()};
  c.limits.maxClients = 6;
  c.limits.maxMessageBytes = 256u << 10;
  c.limits.maxSceneBytes = 1u << 20;
  c.limits.maxPanelPixels = 200'000;  // the builtin Portrait (1536x2048) is refused
  c.limits.maxCaptureFrames = 50;
  c.limits.maxSpp = 16;
  c.sourcePath = "(test)";
  return c;
}

bool readFrame(grpc::ClientReaderInterface<v1::FramePart>& reader, ReceivedFrame& frame) {
  v1::FramePart part;
  if (!reader.Read(&part) || !part.has_header()) return false;
  frame.header = part.header();
  frame.bytes.clear();
  while (frame.bytes.size() < frame.header.total_bytes()) {
    if (!reader.Read(&part) || !part.has_chunk()) return false;
    if (part.chunk().frame_id() != frame.header.frame_id() || part.chunk().offset() != frame.bytes.size()) return false;
    frame.bytes.insert(frame.bytes.end(), part.chunk().data().begin(), part.chunk().data().end());
  }
  return true;
}

std::unique_ptr<v1::Holotrace::Stub> connect(const std::string& address) {
  grpc::ChannelArguments args;
  args.SetMaxReceiveMessageSize(16 << 20);
  return v1::Holotrace::NewStub(grpc::CreateCustomChannel(address, grpc::InsecureChannelCredentials(), args));
}

grpc::Status loadScene(v1::Holotrace::Stub& stub, const std::string& path, v1::SceneHandle* handle) {
  grpc::ClientContext context;
  context.set_deadline(std::chrono::system_clock::now() + std::chrono::seconds(60));
  v1::LoadSceneRequest request;
  request.set_path(path);
  v1::SceneHandle ignored;
  return stub.LoadScene(&context, request, handle ? handle : &ignored);
}

grpc::Status uploadScene(v1::Holotrace::Stub& stub, const std::string& name, const std::string& bytes,
                         v1::SceneHandle* handle) {
  grpc::ClientContext context;
  context.set_deadline(std::chrono::system_clock::now() + std::chrono::seconds(60));
  v1::SceneHandle ignored;
  auto writer = stub.UploadScene(&context, handle ? handle : &ignored);
  v1::UploadSceneChunk chunk;
  chunk.mutable_info()->set_file_name(name);
  chunk.mutable_info()->set_total_bytes(bytes.size());
  writer->Write(chunk);
  chunk.set_data(bytes);
  writer->Write(chunk);
  writer->WritesDone();
  return writer->Finish();
}

v1::RenderRequest tinyRequest(const std::string& sceneId, v1::PixelFormat format) {
  v1::RenderRequest request;
  request.set_scene_id(sceneId);
  request.set_display_id("tiny");
  request.set_format(format);
  request.set_spp(1);
  return request;
}

grpc::Status renderOne(v1::Holotrace::Stub& stub, const v1::RenderRequest& request, ReceivedFrame* frame) {
  grpc::ClientContext context;
  context.set_deadline(std::chrono::system_clock::now() + std::chrono::seconds(60));
  auto reader = stub.RenderFrame(&context, request);
  ReceivedFrame local;
  readFrame(*reader, frame ? *frame : local);
  return reader->Finish();
}

grpc::Status captureFrame(v1::Holotrace::Stub& stub, const std::string& name, const v1::RenderRequest& render,
                          v1::CaptureFormat format, v1::CaptureLayout layout, std::vector<std::string>& files) {
  grpc::ClientContext context;
  context.set_deadline(std::chrono::system_clock::now() + std::chrono::seconds(300));
  v1::CaptureRequest request;
  *request.mutable_render() = render;
  request.set_name(name);
  request.set_frames(1);
  request.set_format(format);
  request.set_layout(layout);
  request.set_overwrite(true);  // callers compare formats and layouts under one name
  auto reader = stub.Capture(&context, request);
  v1::CaptureProgress progress;
  while (reader->Read(&progress)) files.push_back(progress.file());
  return reader->Finish();
}

bool isCompletePng(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  const std::string bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  static const char kSignature[] = "\x89PNG\r\n\x1a\n";
  return bytes.size() > 20 && bytes.compare(0, 8, kSignature, 8) == 0 &&
         bytes.compare(bytes.size() - 8, 4, "IEND") == 0;
}

}  // namespace ht::server::test
