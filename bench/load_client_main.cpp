// load_client_main.cpp - holotrace-bench-load: N concurrent StreamFrames clients against a running holotraced.
// Reports delivered frames/s, per-frame latency (request tick -> last chunk received, from the daemon's
// queue_ms + render_ms plus transfer) and the daemon's VmRSS (/proc/PID/status) before and after.
// Usage: holotrace-bench-load --socket ADDR --pid PID [--clients 8] [--seconds 10] [--fps 30]
//                             [--display ID] [--scene SPEC] [--spp 1]
#include <grpcpp/grpcpp.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iostream>
#include <map>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "holotrace/v1/holotrace.grpc.pb.h"

namespace {

namespace v1 = holotrace::v1;
using Clock = std::chrono::steady_clock;

std::map<std::string, std::string> parseArgs(int argc, char** argv) {
  std::map<std::string, std::string> a = {{"--clients", "8"}, {"--seconds", "10"}, {"--fps", "30"},
                                          {"--display", "builtin:portrait"}, {"--scene", "builtin:plain"},
                                          {"--spp", "1"}, {"--pid", "0"}};
  for (int i = 1; i + 1 < argc; i += 2) a[argv[i]] = argv[i + 1];
  return a;
}

long rssKiB(const std::string& pid) {
  std::ifstream in("/proc/" + pid + "/status");
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("VmRSS:", 0) == 0) return std::stol(line.substr(6));
  }
  return -1;
}

struct Totals {
  std::mutex mutex;
  std::vector<double> latencyMs;
  std::uint64_t frames = 0, dropped = 0, bytes = 0;
};

void runClient(const std::string& address, const v1::StreamRequest& request, Clock::time_point end, Totals& totals) {
  grpc::ChannelArguments args;
  args.SetMaxReceiveMessageSize(64 << 20);
  args.SetInt("grpc.use_local_subchannel_pool", 1);  // one connection per simulated client
  auto stub = v1::Holotrace::NewStub(grpc::CreateCustomChannel(address, grpc::InsecureChannelCredentials(), args));
  grpc::ClientContext context;
  auto reader = stub->StreamFrames(&context, request);
  v1::FramePart part;
  std::uint64_t need = 0, got = 0;
  double latency = 0.0;
  while (Clock::now() < end && reader->Read(&part)) {
    if (part.has_header()) {
      need = part.header().total_bytes();
      got = 0;
      latency = part.header().queue_ms() + part.header().render_ms();
      std::lock_guard lock(totals.mutex);
      totals.dropped += part.header().dropped_frames();
    } else {
      got += part.chunk().data().size();
    }
    if (need > 0 && got == need) {
      std::lock_guard lock(totals.mutex);
      totals.latencyMs.push_back(latency);
      ++totals.frames;
      totals.bytes += need;
      need = 0;
    }
  }
  context.TryCancel();
  while (reader->Read(&part)) {
  }
  reader->Finish();
}

double percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<std::size_t>(p * static_cast<double>(v.size())))];
}

}  // namespace

int main(int argc, char** argv) {
  auto a = parseArgs(argc, argv);
  if (!a.count("--socket")) {
    std::cerr << "usage: holotrace-bench-load --socket ADDR --pid PID [--clients N] [--seconds S] [--fps F]"
                 " [--display ID] [--scene SPEC] [--spp N]\n";
    return 2;
  }
  auto stub = v1::Holotrace::NewStub(grpc::CreateChannel(a["--socket"], grpc::InsecureChannelCredentials()));
  grpc::ClientContext loadContext;
  v1::LoadSceneRequest load;
  load.set_path(a["--scene"]);
  v1::SceneHandle scene;
  const grpc::Status loaded = stub->LoadScene(&loadContext, load, &scene);
  if (!loaded.ok()) {
    std::cerr << "LoadScene: " << loaded.error_message() << "\n";
    return 1;
  }
  v1::StreamRequest request;
  request.mutable_render()->set_scene_id(scene.scene_id());
  request.mutable_render()->set_display_id(a["--display"]);
  request.mutable_render()->set_spp(static_cast<std::uint32_t>(std::stoul(a["--spp"])));
  request.mutable_render()->set_format(v1::PIXEL_FORMAT_RGBA8);
  request.set_frames_per_second(std::stod(a["--fps"]));

  const int clients = std::stoi(a["--clients"]);
  const double seconds = std::stod(a["--seconds"]);
  const long rssBefore = rssKiB(a["--pid"]);
  Totals totals;
  const auto start = Clock::now();
  const auto end = start + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(seconds));
  std::vector<std::thread> threads;
  long rssPeak = rssBefore;
  for (int i = 0; i < clients; ++i) threads.emplace_back(runClient, a["--socket"], request, end, std::ref(totals));
  while (Clock::now() < end) {
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
    rssPeak = std::max(rssPeak, rssKiB(a["--pid"]));
  }
  for (auto& t : threads) t.join();
  const double elapsed = std::chrono::duration<double>(Clock::now() - start).count();
  std::printf("clients %d, %.1f s: %llu frames, %.2f frames/s total (%.2f per client), %.1f MB/s, %llu dropped ticks\n",
              clients, elapsed, static_cast<unsigned long long>(totals.frames), totals.frames / elapsed,
              totals.frames / elapsed / clients, totals.bytes / elapsed / 1e6,
              static_cast<unsigned long long>(totals.dropped));
  std::printf("latency (queue + render) ms: p50 %.1f, p95 %.1f, max %.1f\n", percentile(totals.latencyMs, 0.5),
              percentile(totals.latencyMs, 0.95), percentile(totals.latencyMs, 1.0));
  std::printf("daemon VmRSS: before %ld KiB, peak %ld KiB\n", rssBefore, rssPeak);
  return 0;
}
