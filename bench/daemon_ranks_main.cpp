// daemon_ranks_main.cpp - holotrace-bench-daemon-ranks: what a frame costs a holotraced launched under mpirun
// (docs/CLUSTER.md §8), seen from a client and from the daemon's Status: per frame the client's wall time, rank 0's
// distributed-frame time, the job broadcast (time, bytes), the gather of the other ranks' pixels (time, bytes), and
// every rank's busy time, idle time and work units. Medians over --frames RenderFrame calls after one warm-up frame
// (which sends the scene to the ranks and builds their BVH). Against a single-process daemon it prints the client
// wall time only (Status has no ranks), the same-run baseline of docs/BENCHMARKS.md "holotraced under mpirun".
//
// Usage: holotrace-bench-daemon-ranks --address unix:/path/holotraced.sock [--display ID] [--scene SPEC]
//                                     [--spp N] [--frames N]
#include <grpcpp/grpcpp.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <map>
#include <string>
#include <vector>

#include "bench/timing_series.h"
#include "holotrace/v1/holotrace.grpc.pb.h"

namespace {

namespace v1 = holotrace::v1;
using Clock = std::chrono::steady_clock;
using ht::bench::median;

struct Options {
  std::string address, display = "builtin:holovizio-wall-70", scene = "builtin:showcase";
  std::uint32_t spp = 1, frames = 5;
};

[[noreturn]] void usage(const std::string& problem) {
  std::cerr << "holotrace-bench-daemon-ranks: " << problem
            << "\nUsage: holotrace-bench-daemon-ranks --address ADDR [--display ID] [--scene SPEC] [--spp N] "
               "[--frames N >= 5]\n";
  std::exit(2);
}

Options parseOptions(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string name = argv[i];
    if (i + 1 >= argc) usage(name + " needs a value");
    const std::string value = argv[++i];
    if (name == "--address")
      o.address = value;
    else if (name == "--display")
      o.display = value;
    else if (name == "--scene")
      o.scene = value;
    else if (name == "--spp")
      o.spp = static_cast<std::uint32_t>(std::strtoul(value.c_str(), nullptr, 10));
    else if (name == "--frames")
      o.frames = static_cast<std::uint32_t>(std::strtoul(value.c_str(), nullptr, 10));
    else
      usage("unknown option " + name);
  }
  if (o.address.empty()) usage("--address is required");
  if (o.frames < 5) usage("--frames must be >= 5 (medians)");
  if (o.spp < 1) usage("--spp must be >= 1");
  return o;
}

void check(const grpc::Status& status, const char* call) {
  if (status.ok()) return;
  std::cerr << "holotrace-bench-daemon-ranks: " << call << ": " << status.error_message() << "\n";
  std::exit(1);
}

// One RenderFrame, read to the end; returns the client's wall time in ms.
double renderFrame(v1::Holotrace::Stub& stub, const v1::RenderRequest& request) {
  const auto start = Clock::now();
  grpc::ClientContext context;
  auto reader = stub.RenderFrame(&context, request);
  v1::FramePart part;
  while (reader->Read(&part)) {}
  check(reader->Finish(), "RenderFrame");
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

v1::StatusResponse status(v1::Holotrace::Stub& stub) {
  grpc::ClientContext context;
  v1::StatusResponse response;
  check(stub.Status(&context, {}, &response), "Status");
  return response;
}

struct Series {
  std::vector<double> client, frame, broadcast, broadcastBytes, gather, gatherBytes, units;
  std::map<std::uint32_t, std::vector<double>> busy, idle, rankUnits;
};

void printSeries(const Options& o, const Series& s, std::size_t ranks) {
  std::printf("%u frames of %s (%s, spp %u), medians:\n", o.frames, o.display.c_str(), o.scene.c_str(), o.spp);
  std::printf("  client RenderFrame wall      %9.2f ms\n", median(s.client));
  if (ranks == 0) {
    std::printf("  (a single-process daemon: no ranks in Status)\n");
    return;
  }
  std::printf("  rank 0 distributed frame     %9.2f ms  (%zu ranks, %.0f work units)\n", median(s.frame), ranks,
              median(s.units));
  std::printf("  job broadcast                %9.3f ms  %10.0f bytes\n", median(s.broadcast), median(s.broadcastBytes));
  std::printf("  gather to rank 0             %9.2f ms  %10.0f bytes\n", median(s.gather), median(s.gatherBytes));
  for (const auto& [rank, busy] : s.busy) {
    std::printf("  rank %u: busy %9.2f ms, idle %9.2f ms, %5.1f units\n", rank, median(busy), median(s.idle.at(rank)),
                median(s.rankUnits.at(rank)));
  }
}

}  // namespace

int main(int argc, char** argv) {
  const Options o = parseOptions(argc, argv);
  grpc::ChannelArguments args;
  args.SetMaxReceiveMessageSize(256 << 20);
  auto stub = v1::Holotrace::NewStub(grpc::CreateCustomChannel(o.address, grpc::InsecureChannelCredentials(), args));
  v1::SceneHandle handle;
  {
    grpc::ClientContext context;
    v1::LoadSceneRequest request;
    request.set_path(o.scene);
    check(stub->LoadScene(&context, request, &handle), "LoadScene");
  }
  v1::RenderRequest request;
  request.set_scene_id(handle.scene_id());
  request.set_display_id(o.display);
  request.set_spp(o.spp);
  renderFrame(*stub, request);  // warm-up: kernels, the scene's bytes to the ranks, their BVH
  Series s;
  std::size_t ranks = 0;
  for (std::uint32_t f = 0; f < o.frames; ++f) {
    request.set_seed(f + 1);
    s.client.push_back(renderFrame(*stub, request));
    const v1::StatusResponse st = status(*stub);
    ranks = static_cast<std::size_t>(st.ranks_size());
    const v1::ClusterFrameStatus& c = st.cluster();
    s.frame.push_back(c.last_frame_ms());
    s.broadcast.push_back(c.last_broadcast_ms());
    s.broadcastBytes.push_back(static_cast<double>(c.last_broadcast_bytes()));
    s.gather.push_back(c.last_gather_ms());
    s.gatherBytes.push_back(static_cast<double>(c.last_gather_bytes()));
    s.units.push_back(c.work_units());
    for (const v1::RankStatus& r : st.ranks()) {
      s.busy[r.rank()].push_back(r.last_busy_ms());
      s.idle[r.rank()].push_back(r.last_idle_ms());
      s.rankUnits[r.rank()].push_back(r.last_units());
    }
  }
  printSeries(o, s, ranks);
  return 0;
}
