// load_client_main.cpp - holotrace-bench-load: N concurrent StreamFrames clients against a running holotraced.
// Reports delivered frames/s, per-frame latency (the daemon's queue_ms + render_ms), the daemon's RSS over the run
// (sampled through Status: first / last / max after warm-up and the slope per 1000 frames, which a leak makes
// positive), and the daemon's CPU time per frame against the same frames rendered in-process (--baseline-frames):
// the difference is what the protocol costs. Options: bench/load_options.cpp.
#include <grpcpp/grpcpp.h>

#include <algorithm>
#include <cstdio>
#include <iostream>
#include <thread>
#include <vector>

#include "bench/load_inprocess.h"
#include "bench/load_options.h"
#include "bench/load_rss_series.h"
#include "bench/load_stream_client.h"
#include "holotrace/v1/holotrace.grpc.pb.h"

namespace {

namespace v1 = holotrace::v1;
using ht::bench::DaemonSample;
using Clock = std::chrono::steady_clock;

v1::StatusResponse daemonStatus(v1::Holotrace::Stub& stub) {
  grpc::ClientContext context;
  context.set_deadline(std::chrono::system_clock::now() + std::chrono::seconds(10));
  v1::StatusResponse status;
  const grpc::Status s = stub.Status(&context, {}, &status);
  if (!s.ok()) throw std::runtime_error("Status: " + s.error_message());
  return status;
}

DaemonSample sample(v1::Holotrace::Stub& stub, Clock::time_point start, const ht::bench::LoadTotals& totals) {
  const std::uint64_t frames = totals.frames.load();
  const v1::StatusResponse status = daemonStatus(stub);
  return {std::chrono::duration<double>(Clock::now() - start).count(), frames, status.resident_kib(),
          status.cpu_seconds(), status.threads()};
}

v1::StreamRequest streamRequest(v1::Holotrace::Stub& stub, const ht::bench::LoadOptions& o) {
  grpc::ClientContext context;
  v1::LoadSceneRequest load;
  load.set_path(o.scene);
  v1::SceneHandle scene;
  const grpc::Status loaded = stub.LoadScene(&context, load, &scene);
  if (!loaded.ok()) throw std::runtime_error("LoadScene: " + loaded.error_message());
  v1::StreamRequest request;
  request.set_mode(v1::STREAM_MODE_INDEPENDENT);  // continuous frames (progressive converges and goes quiet)
  request.mutable_render()->set_scene_id(scene.scene_id());
  request.mutable_render()->set_display_id(o.display);
  request.mutable_render()->set_spp(o.spp);
  request.mutable_render()->set_format(v1::PIXEL_FORMAT_RGBA8);
  request.set_frames_per_second(o.fps);
  return request;
}

double percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<std::size_t>(p * static_cast<double>(v.size())))];
}

void printThroughput(const ht::bench::LoadOptions& o, const ht::bench::LoadTotals& t, double elapsed) {
  const double frames = static_cast<double>(t.frames.load());
  std::printf(
      "clients %d, %.1f s: %llu frames, %.2f frames/s total (%.2f per client), %.2f MB/s, %llu calls "
      "(%llu failed), %llu dropped ticks\n",
      o.clients, elapsed, static_cast<unsigned long long>(t.frames.load()), frames / elapsed,
      frames / elapsed / o.clients, static_cast<double>(t.bytes) / elapsed / 1e6,
      static_cast<unsigned long long>(t.calls.load()), static_cast<unsigned long long>(t.failedCalls),
      static_cast<unsigned long long>(t.dropped));
  if (!t.lastError.empty()) std::printf("last call error: %s\n", t.lastError.c_str());
  std::printf("latency (queue + render) ms: p50 %.1f, p95 %.1f, max %.1f\n", percentile(t.latencyMs, 0.5),
              percentile(t.latencyMs, 0.95), percentile(t.latencyMs, 1.0));
}

void printDaemon(const std::vector<DaemonSample>& samples, std::uint64_t frames) {
  const DaemonSample& a = samples.front();
  const DaemonSample& b = samples.back();
  const auto all = ht::bench::summarizeRss(samples, 0);
  const auto steady = ht::bench::summarizeRss(samples, frames / 10);
  std::printf(
      "daemon VmRSS KiB: before %llu, max %llu, end %llu; after 10%% warm-up (%zu samples): first %llu, "
      "last %llu, max %llu, slope %+.1f KiB per 1000 frames\n",
      static_cast<unsigned long long>(a.rssKiB), static_cast<unsigned long long>(all.maxKiB),
      static_cast<unsigned long long>(b.rssKiB), steady.samplesUsed, static_cast<unsigned long long>(steady.firstKiB),
      static_cast<unsigned long long>(steady.lastKiB), static_cast<unsigned long long>(steady.maxKiB),
      steady.slopeKiBPer1000Frames);
  std::printf("daemon threads: before %u, end %u; daemon CPU %.1f s = %.2f ms per frame\n", a.threads, b.threads,
              b.cpuSeconds - a.cpuSeconds, 1e3 * (b.cpuSeconds - a.cpuSeconds) / std::max<double>(1, frames));
}

void printBaseline(const ht::bench::InProcessRun& base, const std::vector<DaemonSample>& samples, double elapsed,
                   std::uint64_t frames) {
  const double baseCpuMs = 1e3 * base.cpuSeconds / static_cast<double>(base.frames);
  const double daemonCpuMs =
      1e3 * (samples.back().cpuSeconds - samples.front().cpuSeconds) / std::max<double>(1, frames);
  std::printf(
      "in-process baseline: %llu frames, %.2f frames/s, %.2f ms CPU per frame; through the daemon: "
      "%.2f frames/s, %.2f ms CPU per frame -> protocol %+.2f ms CPU per frame (%+.0f%%)\n",
      static_cast<unsigned long long>(base.frames), static_cast<double>(base.frames) / base.wallSeconds, baseCpuMs,
      static_cast<double>(frames) / elapsed, daemonCpuMs, daemonCpuMs - baseCpuMs,
      100.0 * (daemonCpuMs - baseCpuMs) / baseCpuMs);
}

int run(const ht::bench::LoadOptions& o) {
  ht::bench::InProcessRun base;
  if (o.baselineFrames > 0)
    base = ht::bench::renderInProcess(o.displaysDir, o.display, o.scene, o.spp, o.baselineFrames);
  auto stub = v1::Holotrace::NewStub(grpc::CreateChannel(o.socket, grpc::InsecureChannelCredentials()));
  const v1::StreamRequest request = streamRequest(*stub, o);
  ht::bench::LoadTotals totals;
  const auto start = Clock::now();
  const auto limit = std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(o.seconds));
  const ht::bench::LoadStop stop{o.seconds > 0 ? start + limit : Clock::time_point::max(), o.frames};
  std::vector<DaemonSample> samples{sample(*stub, start, totals)};
  std::vector<std::thread> threads;
  for (int i = 0; i < o.clients; ++i) {
    threads.emplace_back(ht::bench::runStreamClient, o.socket, request, std::cref(stop), o.reconnectEvery,
                         std::ref(totals));
  }
  while (!stop.reached(totals)) {
    std::this_thread::sleep_for(std::chrono::milliseconds(o.sampleMs));
    samples.push_back(sample(*stub, start, totals));
  }
  for (auto& t : threads) t.join();
  const double elapsed = std::chrono::duration<double>(Clock::now() - start).count();
  samples.push_back(sample(*stub, start, totals));
  if (!o.samplesCsv.empty()) ht::bench::writeSamplesCsv(samples, o.samplesCsv);
  printThroughput(o, totals, elapsed);
  printDaemon(samples, totals.frames.load());
  if (o.baselineFrames > 0) printBaseline(base, samples, elapsed, totals.frames.load());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(ht::bench::parseLoadOptions(argc, argv));
  } catch (const std::invalid_argument& e) {
    std::cerr << "holotrace-bench-load: " << e.what() << "\n" << ht::bench::kLoadUsage;
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "holotrace-bench-load: " << e.what() << "\n";
    return 1;
  }
}
