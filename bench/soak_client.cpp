// soak_client.cpp - see soak_client.h.
#include "bench/soak_client.h"

#include <grpcpp/grpcpp.h>

#include <chrono>
#include <random>
#include <sstream>
#include <thread>
#include <vector>

#include "bench/soak_daemon.h"
#include "holotrace/v1/holotrace.grpc.pb.h"

namespace ht::bench {
namespace {

namespace v1 = holotrace::v1;
using grpc::StatusCode;
using Stub = v1::Holotrace::Stub;

// Codes a well-behaved daemon may answer under this load: refusals at a limit, sessions ended by the TTL or LRU,
// calls cancelled by the client or by the daemon's stall watchdog.
bool expected(int code) {
  return code == static_cast<int>(StatusCode::OK) || code == static_cast<int>(StatusCode::CANCELLED) ||
         code == static_cast<int>(StatusCode::RESOURCE_EXHAUSTED) || code == static_cast<int>(StatusCode::NOT_FOUND);
}

std::unique_ptr<Stub> newClient(const std::string& address, bool bdpProbe = true) {
  grpc::ChannelArguments args;
  args.SetMaxReceiveMessageSize(64 << 20);
  if (!bdpProbe) args.SetInt("grpc.http2.bdp_probe", 0);
  return v1::Holotrace::NewStub(grpc::CreateCustomChannel(address, grpc::InsecureChannelCredentials(), args));
}

void deadline(grpc::ClientContext& context, int seconds = 60) {
  context.set_deadline(std::chrono::system_clock::now() + std::chrono::seconds(seconds));
}

struct Worker {
  const SoakTarget& target;
  int id;
  std::mt19937_64 rng;
  SoakTally& tally;
  std::uint64_t serial = 0;

  int pick(int n) { return static_cast<int>(rng() % static_cast<std::uint64_t>(n)); }

  std::string sceneSpec() {
    if (!target.hasGridScenes || pick(3) == 0) return "builtin:plain";
    return "grid" + std::to_string(pick(6)) + ".obj";
  }

  v1::RenderRequest request(const std::string& sceneId) {
    v1::RenderRequest r;
    r.set_scene_id(sceneId);
    r.set_display_id(target.display);
    r.set_spp(1);
    return r;
  }

  std::string load(Stub& stub) {
    grpc::ClientContext context;
    deadline(context);
    v1::LoadSceneRequest req;
    req.set_path(sceneSpec());
    v1::SceneHandle handle;
    const grpc::Status s = stub.LoadScene(&context, req, &handle);
    tally.count("load", s.error_code(), s.error_message());
    return s.ok() ? handle.scene_id() : "";
  }

  void unload(Stub& stub, const std::string& sceneId) {
    grpc::ClientContext context;
    deadline(context);
    v1::UnloadSceneRequest req;
    req.set_scene_id(sceneId);
    v1::UnloadSceneResponse response;
    const grpc::Status s = stub.UnloadScene(&context, req, &response);
    tally.count("unload", s.error_code(), s.error_message());
  }

  bool render(Stub& stub, const std::string& sceneId) {
    grpc::ClientContext context;
    deadline(context);
    auto reader = stub.RenderFrame(&context, request(sceneId));
    v1::FramePart part;
    while (reader->Read(&part)) {}
    const grpc::Status s = reader->Finish();
    tally.count("render", s.error_code(), s.error_message());
    return s.ok();
  }

  void loadRender() {
    auto stub = newClient(target.address);
    const std::string sceneId = load(*stub);
    if (sceneId.empty()) return;
    if (render(*stub, sceneId)) tally.addCycle();
    if (pick(2) == 0) unload(*stub, sceneId);  // else the client just goes away
  }

  std::string uploadBytes() { return soakGridObj(20 + pick(4) * 10, 100 + pick(4)); }

  void upload() {
    auto stub = newClient(target.address);
    grpc::ClientContext context;
    deadline(context);
    v1::SceneHandle handle;
    auto writer = stub->UploadScene(&context, &handle);
    const std::string bytes = uploadBytes();
    v1::UploadSceneChunk chunk;
    chunk.mutable_info()->set_file_name("soak.obj");
    chunk.mutable_info()->set_total_bytes(bytes.size());
    writer->Write(chunk);
    for (std::size_t at = 0; at < bytes.size(); at += 64 << 10) {
      chunk.set_data(bytes.substr(at, 64 << 10));
      if (!writer->Write(chunk)) break;
    }
    writer->WritesDone();
    const grpc::Status s = writer->Finish();
    tally.count("upload", s.error_code(), s.error_message());
    if (!s.ok()) return;
    if (render(*stub, handle.scene_id())) tally.addCycle();
    unload(*stub, handle.scene_id());
  }

  // Streams `frames` frames; then cancels (and reads the status) or vanishes (cancels and drops the call).
  void stream(bool pauseReader) {
    auto stub = newClient(target.address, !pauseReader);
    const std::string sceneId = load(*stub);
    if (sceneId.empty()) return;
    grpc::ClientContext context;
    deadline(context);
    v1::StreamRequest req;
    req.set_mode(v1::STREAM_MODE_INDEPENDENT);  // continuous frames (progressive converges and goes quiet)
    *req.mutable_render() = request(sceneId);
    req.set_frames_per_second(pauseReader ? 120 : 30 + pick(60));
    auto reader = stub->StreamFrames(&context, req);
    v1::FramePart part;
    const int parts = pauseReader ? 2 : 5 + pick(30);
    for (int i = 0; i < parts && reader->Read(&part); ++i) {}
    if (pauseReader) std::this_thread::sleep_for(std::chrono::milliseconds(500 + pick(2500)));  // past the stall limit
    context.TryCancel();
    if (!pauseReader && pick(2) == 0) return;  // vanished: no Finish, the channel closes
    while (reader->Read(&part)) {}
    const grpc::Status s = reader->Finish();
    tally.count(pauseReader ? "paused-stream" : "stream", s.error_code(), s.error_message());
  }

  void capture() {
    if (target.outputRoot.empty()) return;
    auto stub = newClient(target.address);
    const std::string sceneId = load(*stub);
    if (sceneId.empty()) return;
    const std::string name = "soak-w" + std::to_string(id) + "-" + std::to_string(serial++);
    grpc::ClientContext context;
    deadline(context);
    v1::CaptureRequest req;
    *req.mutable_render() = request(sceneId);
    req.set_name(name);
    req.set_frames(1 + static_cast<std::uint32_t>(pick(3)));
    auto reader = stub->Capture(&context, req);
    v1::CaptureProgress progress;
    const bool cancel = pick(3) == 0;
    while (reader->Read(&progress)) {
      if (cancel) context.TryCancel();
    }
    const grpc::Status s = reader->Finish();
    tally.count("capture", s.error_code(), s.error_message());
    std::error_code ec;  // the captured files go again (the disk stays as it was)
    for (const auto& entry : std::filesystem::directory_iterator(target.outputRoot, ec)) {
      if (entry.path().filename().string().rfind(name + "_", 0) == 0) std::filesystem::remove(entry.path(), ec);
    }
  }

  void stalledUpload() {
    auto stub = newClient(target.address);
    grpc::ClientContext context;
    deadline(context);
    v1::SceneHandle handle;
    auto writer = stub->UploadScene(&context, &handle);
    v1::UploadSceneChunk chunk;
    chunk.mutable_info()->set_file_name("stalled.obj");
    chunk.mutable_info()->set_total_bytes(4u << 20);  // declared, never sent: reserved in the daemon's budget
    writer->Write(chunk);
    std::this_thread::sleep_for(std::chrono::milliseconds(300 + pick(2700)));
    context.TryCancel();
    const grpc::Status s = writer->Finish();
    tally.count("stalled-upload", s.error_code(), s.error_message());
  }

  void status() {
    auto stub = newClient(target.address);
    grpc::ClientContext context;
    deadline(context);
    v1::ListDisplaysResponse displays;
    const grpc::Status s = stub->ListDisplays(&context, {}, &displays);
    tally.count("list", s.error_code(), s.error_message());
  }

  void act() {
    const int roll = target.loadRenderOnly ? 0 : pick(100);
    if (roll < 35)
      loadRender();
    else if (roll < 50)
      upload();
    else if (roll < 65)
      stream(false);
    else if (roll < 75)
      capture();
    else if (roll < 80)
      stalledUpload();
    else if (roll < 85)
      stream(true);
    else
      status();
  }
};

}  // namespace

void SoakTally::count(const std::string& action, int grpcCode, const std::string& message) {
  std::lock_guard lock(mutex_);
  ++counts_[action][grpcCode];
  if (!expected(grpcCode) && !firstFailure_.count(action)) {
    firstFailure_[action] = "code " + std::to_string(grpcCode) + ": " + message;
  }
}

std::uint64_t SoakTally::failures() const {
  std::lock_guard lock(mutex_);
  std::uint64_t n = 0;
  for (const auto& [action, codes] : counts_) {
    for (const auto& [code, count] : codes) n += expected(code) ? 0 : count;
  }
  return n;
}

std::string SoakTally::report() const {
  std::lock_guard lock(mutex_);
  std::ostringstream out;
  for (const auto& [action, codes] : counts_) {
    out << "  " << action << ":";
    for (const auto& [code, count] : codes) out << " " << count << " x code " << code;
    out << "\n";
  }
  for (const auto& [action, failure] : firstFailure_) out << "  first failure of " << action << ": " << failure << "\n";
  return out.str();
}

void runSoakWorker(const SoakTarget& target, std::uint64_t seed, int worker, const std::atomic<bool>& stop,
                   SoakTally& tally) {
  Worker w{target, worker, std::mt19937_64(seed * 1000003 + static_cast<std::uint64_t>(worker)), tally};
  while (!stop.load()) w.act();
}

}  // namespace ht::bench
