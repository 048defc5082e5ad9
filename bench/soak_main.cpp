// soak_main.cpp - holotrace-soak: holotraced under a long mixed load (bench/soak_options.h for the command line,
// docs/SERVICE.md §10). Mixed clients (bench/soak_client.h) run for a warm-up, the daemon is left to come to rest
// and measured (RSS, threads, open fds through Status), the clients run for --seconds, the daemon comes to rest again
// and is measured again. Exit 0 only if nothing failed unexpectedly and the two at-rest measurements match within
// the tolerances ("flat"); 1 otherwise; 2 for a bad command line.
#include <grpcpp/grpcpp.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "bench/load_rss_series.h"
#include "bench/soak_client.h"
#include "bench/soak_daemon.h"
#include "bench/soak_options.h"
#include "holotrace/v1/holotrace.grpc.pb.h"

namespace ht::bench {
namespace {

namespace v1 = holotrace::v1;
using Clock = std::chrono::steady_clock;

struct Sample {
  double seconds = 0;
  v1::StatusResponse status;
  std::uint64_t cycles = 0;
};

std::optional<v1::StatusResponse> daemonStatus(v1::Holotrace::Stub& stub) {
  grpc::ClientContext context;
  context.set_deadline(std::chrono::system_clock::now() + std::chrono::seconds(10));
  v1::StatusResponse response;
  if (!stub.Status(&context, {}, &response).ok()) return std::nullopt;
  return response;
}

v1::StatusResponse waitReady(v1::Holotrace::Stub& stub) {
  const auto until = Clock::now() + std::chrono::seconds(60);
  while (Clock::now() < until) {
    if (auto s = daemonStatus(stub)) return *s;
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  throw std::runtime_error("holotraced did not answer Status within 60 s");
}

// Runs the workers for `seconds`, or until `tally` counts `cycles` load/render cycles (cycles > 0) if sooner.
void runClients(const SoakTarget& target, const SoakOptions& o, std::uint64_t seed, double seconds,
                std::uint64_t cycles, SoakTally& tally) {
  std::atomic<bool> stop{false};
  std::vector<std::thread> workers;
  for (int i = 0; i < o.clients; ++i) {
    workers.emplace_back([&, i] { runSoakWorker(target, seed, i, stop, tally); });
  }
  const auto until = Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(seconds));
  while (Clock::now() < until && (cycles == 0 || tally.loadRenderCycles() < cycles)) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  stop = true;
  for (std::thread& w : workers) w.join();
}

// Waits for running calls to end and idle sessions to expire; then measures.
v1::StatusResponse atRest(v1::Holotrace::Stub& stub, double quiesceSeconds) {
  const auto until = Clock::now() + std::chrono::seconds(30);
  while (Clock::now() < until) {
    auto s = daemonStatus(stub);
    if (s && s->active_streams() == 0) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  std::this_thread::sleep_for(std::chrono::duration<double>(quiesceSeconds));
  auto s = daemonStatus(stub);
  if (!s) throw std::runtime_error("holotraced stopped answering Status");
  return *s;
}

class Sampler {
 public:
  Sampler(v1::Holotrace::Stub& stub, double period, const SoakTally& tally) {
    thread_ = std::thread([this, &stub, period, &tally] {
      const auto start = Clock::now();
      while (!stop_.load()) {
        if (auto s = daemonStatus(stub)) {
          samples_.push_back(
              {std::chrono::duration<double>(Clock::now() - start).count(), *s, tally.loadRenderCycles()});
        }
        for (double waited = 0; waited < period && !stop_.load(); waited += 0.05) {
          std::this_thread::sleep_for(std::chrono::milliseconds(50));
        }
      }
    });
  }
  std::vector<Sample> finish() {
    stop_ = true;
    thread_.join();
    return samples_;
  }

 private:
  std::atomic<bool> stop_{false};
  std::vector<Sample> samples_;
  std::thread thread_;
};

void writeCsv(const std::vector<Sample>& samples, const std::string& file) {
  std::ofstream out(file);
  out << "seconds,rss_kib,threads,fds,sessions,scene_mib,cycles\n";
  for (const Sample& s : samples) {
    out << s.seconds << "," << s.status.resident_kib() << "," << s.status.threads() << "," << s.status.open_fds() << ","
        << s.status.scene_sessions() << "," << s.status.scene_memory_bytes() / 1048576.0 << "," << s.cycles << "\n";
  }
  if (!out) throw std::runtime_error("cannot write " + file);
}

// RSS slope over the samples from `fromSeconds` on, KiB per minute.
double rssSlope(const std::vector<Sample>& samples, double fromSeconds) {
  std::vector<double> x, y;
  for (const Sample& s : samples) {
    if (s.seconds < fromSeconds) continue;
    x.push_back(s.seconds / 60.0);
    y.push_back(static_cast<double>(s.status.resident_kib()));
  }
  return leastSquaresSlope(x, y);
}

bool check(bool ok, const std::string& what) {
  std::cout << (ok ? "  ok    " : "  FAIL  ") << what << "\n";
  return ok;
}

int soak(const SoakOptions& o) {
  std::unique_ptr<SoakDaemon> spawned;
  SoakTarget target{o.socket, o.display, o.outputRoot, false, o.loadRenderOnly};
  if (!o.daemonExe.empty()) {
    spawned = std::make_unique<SoakDaemon>(o.daemonExe, o.displaysDir);
    target = {spawned->address(), o.display, spawned->outputRoot(), true, o.loadRenderOnly};
  }
  const double quiesce = o.quiesceSeconds > 0 ? o.quiesceSeconds : spawned ? kSoakSceneIdleSeconds + 1.5 : 5.0;
  auto stub = v1::Holotrace::NewStub(grpc::CreateChannel(target.address, grpc::InsecureChannelCredentials()));
  const v1::StatusResponse start = waitReady(*stub);
  std::cout << "holotrace-soak: daemon pid " << start.pid() << " at " << target.address << ", " << o.clients
            << " clients, warm-up " << o.warmupSeconds << " s, run " << o.seconds << " s\n";
  SoakTally tally;
  Sampler sampler(*stub, o.sampleSeconds, tally);
  const auto t0 = Clock::now();
  runClients(target, o, o.seed, o.warmupSeconds, 0, tally);
  const v1::StatusResponse base = atRest(*stub, quiesce);
  const double mainFrom = std::chrono::duration<double>(Clock::now() - t0).count();
  const std::uint64_t warmCycles = tally.loadRenderCycles();
  runClients(target, o, o.seed + 1, o.seconds, o.cycles == 0 ? 0 : warmCycles + o.cycles, tally);
  const v1::StatusResponse end = atRest(*stub, quiesce);
  const std::vector<Sample> samples = sampler.finish();
  if (!o.samplesCsv.empty()) writeCsv(samples, o.samplesCsv);

  std::uint64_t peakRss = 0;
  std::uint32_t peakThreads = 0, peakFds = 0;
  for (const Sample& s : samples) {
    peakRss = std::max<std::uint64_t>(peakRss, s.status.resident_kib());
    peakThreads = std::max(peakThreads, s.status.threads());
    peakFds = std::max(peakFds, s.status.open_fds());
  }
  std::cout << "calls (gRPC status code counts; 0 OK, 1 CANCELLED, 5 NOT_FOUND, 8 RESOURCE_EXHAUSTED):\n"
            << tally.report();
  std::cout << "load/render cycles: " << tally.loadRenderCycles()
            << "; sessions released by the daemon: " << end.scene_sessions_released() << "; samples: " << samples.size()
            << "\n";
  std::printf("at rest after warm-up: RSS %.1f MiB, %u threads, %u fds, %u sessions\n", base.resident_kib() / 1024.0,
              base.threads(), base.open_fds(), base.scene_sessions());
  std::printf("at rest at the end:    RSS %.1f MiB, %u threads, %u fds, %u sessions\n", end.resident_kib() / 1024.0,
              end.threads(), end.open_fds(), end.scene_sessions());
  std::printf("peak under load: RSS %.1f MiB, %u threads, %u fds; RSS slope over the run %.1f KiB/min\n",
              peakRss / 1024.0, peakThreads, peakFds, rssSlope(samples, mainFrom));
  const std::uint64_t rssAllowance = std::max<std::uint64_t>(o.rssToleranceKiB, base.resident_kib() / 10);
  bool ok = check(tally.failures() == 0, std::to_string(tally.failures()) + " unexpected failures");
  ok &= check(
      end.resident_kib() <= base.resident_kib() + rssAllowance,
      "RSS at rest grew " +
          std::to_string(static_cast<long long>(end.resident_kib()) - static_cast<long long>(base.resident_kib())) +
          " KiB (allowed " + std::to_string(rssAllowance) + ")");
  ok &= check(end.threads() <= base.threads() + o.threadTolerance,
              "threads at rest " + std::to_string(base.threads()) + " -> " + std::to_string(end.threads()));
  ok &= check(end.open_fds() <= base.open_fds() + o.fdTolerance,
              "open fds at rest " + std::to_string(base.open_fds()) + " -> " + std::to_string(end.open_fds()));
  ok &= check(end.scene_sessions() == 0 || !spawned, "no sessions left after the idle TTL");
  if (spawned) {
    const int exitCode = spawned->stop();
    ok &= check(exitCode == 0, "holotraced exits 0 on SIGTERM (got " + std::to_string(exitCode) + ")");
    if (!ok) std::cout << "daemon log: " << spawned->logFile() << " (removed at exit)\n";
  }
  std::cout << (ok ? "holotrace-soak: flat\n" : "holotrace-soak: NOT flat\n");
  return ok ? 0 : 1;
}

}  // namespace
}  // namespace ht::bench

int main(int argc, char** argv) {
  if (argc == 2 && (std::string(argv[1]) == "--help" || std::string(argv[1]) == "-h")) {
    std::cout << ht::bench::kSoakUsage;
    return 0;
  }
  ht::bench::SoakOptions options;
  try {
    options = ht::bench::parseSoakOptions(argc, argv);
  } catch (const std::invalid_argument& e) {
    std::cerr << "holotrace-soak: " << e.what() << "\n" << ht::bench::kSoakUsage;
    return 2;
  }
  try {
    return ht::bench::soak(options);
  } catch (const std::exception& e) {
    std::cerr << "holotrace-soak: " << e.what() << "\n";
    return 1;
  }
}
