// bench_wall_main.cpp - holotrace-bench-wall: the live wall's swap barrier (docs/CLUSTER.md §7) on this machine. It
// starts a private Xvfb with one RandR monitor per rank, runs `mpirun -np N holotrace wall` (shared memory and
// loopback only) --runs times per rank count, reads each run's report and prints, per rank count, the median over
// the runs of each run's per-frame medians:
//   - barrier cost: the wait of the last rank to enter the swap barrier (the others were already there);
//   - release skew: latest minus earliest rank to see the barrier complete;
//   - flip skew: latest minus earliest rank to have its present issued to the display (vkQueuePresentKHR returned);
//   - rank 0's render, barrier wait and present times per frame.
// The wall is a row of small projectors (--projectors P of --view WxH, P / N per rank), so rendering stays short and
// the swap dominates. Timings come from the wall's own job clock (docs/CLUSTER.md §7).
//
// Usage: holotrace-bench-wall [--ranks 2,3] [--runs 5] [--frames 40] [--projectors 6] [--view 64x48]
//                             [--swap-timeout 1000] [--holotrace PATH] [--mpirun PATH]
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "bench/bench_main.h"
#include "cli/arguments.h"
#include "cluster/wall_report.h"
#include "present/xvfb_server.h"

namespace ht::bench {
namespace {

namespace fs = std::filesystem;

struct WallBenchOptions {
  std::vector<int> ranks = {2, 3};
  std::uint32_t runs = 5, frames = 40, projectors = 6, viewWidth = 64, viewHeight = 48, swapTimeoutMs = 1000;
  std::string holotrace = HOLOTRACE_EXE, mpirun = MPIEXEC_EXE;
};

const std::vector<cli::OptionSpec> kSpecs = {
    {"--ranks", "", "LIST", "rank counts, comma-separated (default 2,3)"},
    {"--runs", "", "N", "mpirun jobs per rank count, median reported (default 5)"},
    {"--frames", "", "N", "frames per job (default 40)"},
    {"--projectors", "", "P", "projectors of the wall, split over the ranks (default 6)"},
    {"--view", "", "WxH", "one projector's image (default 64x48)"},
    {"--swap-timeout", "", "MS", "the wall's --swap-timeout (default 1000: no frame times out)"},
    {"--holotrace", "", "PATH", "the holotrace binary (default: the one built with this program)"},
    {"--mpirun", "", "PATH", "the MPI launcher (default: the one CMake found)"},
};

std::optional<WallBenchOptions> parse(const std::vector<std::string>& args, std::string* help) {
  if (cli::wantsHelp(args)) {
    *help =
        "holotrace-bench-wall: swap barrier cost and flip skew of `holotrace wall` under mpirun "
        "(docs/BENCHMARKS.md)\n\n" +
        cli::formatOptions(kSpecs);
    return std::nullopt;
  }
  const cli::ParsedArguments p = cli::parseArguments("holotrace-bench-wall", kSpecs, args);
  WallBenchOptions o;
  if (auto list = p.text("--ranks")) {
    o.ranks.clear();
    std::stringstream in(*list);
    std::string item;
    while (std::getline(in, item, ',')) {
      const int n = std::atoi(item.c_str());
      if (n < 1 || n > 64) throw UsageError("holotrace-bench-wall: option '--ranks' = '" + *list + "': expected 1-64");
      o.ranks.push_back(n);
    }
  }
  o.runs = p.unsignedValue("--runs", 1, 1000).value_or(o.runs);
  o.frames = p.unsignedValue("--frames", 1, 100000).value_or(o.frames);
  o.projectors = p.unsignedValue("--projectors", 1, 256).value_or(o.projectors);
  if (auto view = p.text("--view")) {
    if (std::sscanf(view->c_str(), "%ux%u", &o.viewWidth, &o.viewHeight) != 2 || o.viewWidth == 0 ||
        o.viewHeight == 0 || o.viewWidth > 4096 || o.viewHeight > 4096)
      throw UsageError("holotrace-bench-wall: option '--view' = '" + *view + "': expected WxH, e.g. 64x48");
  }
  o.swapTimeoutMs = p.unsignedValue("--swap-timeout", 1, 600000).value_or(o.swapTimeoutMs);
  o.holotrace = p.textOr("--holotrace", o.holotrace);
  o.mpirun = p.textOr("--mpirun", o.mpirun);
  return o;
}

std::string wallConfig(const WallBenchOptions& o) {
  std::ostringstream s;
  s << R"({"name": "bench-wall", "model": "projector-array", "camera": {"target": "auto", "size": "auto"}, "spp": 1,
  "projectorArray": {"screen": {"width": 1600, "height": 900}, "observerDistance": 3000, "observerHeight": 0,
  "angularScattering": "auto", "image": {"width": )"
    << o.viewWidth << R"(, "height": )" << o.viewHeight << R"(}, "projectors": [)";
  for (std::uint32_t p = 0; p < o.projectors; ++p)
    s << (p ? ", " : "") << "{\"position\": [" << (double(p) - (o.projectors - 1) / 2.0) * 32.0 << ", 0, -1800]}";
  s << "]}}";
  return s.str();
}

struct RunFigures {
  double costUs = 0, releaseUs = 0, flipUs = 0, flipMaxUs = 0, renderMs = 0, waitMs = 0, presentMs = 0;
  unsigned synced = 0;
};

RunFigures parseReport(const std::string& out) {
  RunFigures f;
  const auto swap = out.find("  swap: ");
  const auto rank0 = out.find("  rank 0: presented");
  if (swap == std::string::npos || rank0 == std::string::npos)
    throw Error("the wall printed no report:\n" + out.substr(out.size() > 4000 ? out.size() - 4000 : 0));
  std::sscanf(out.c_str() + swap,
              "  swap: %u frame(s) shown by every rank on time; barrier cost median %lf us (the last rank's wait), "
              "release skew median %lf us, flip skew median %lf us (max %lf us)",
              &f.synced, &f.costUs, &f.releaseUs, &f.flipUs, &f.flipMaxUs);
  const auto medians = out.find("median render", rank0);
  std::sscanf(out.c_str() + medians, "median render %lf ms, barrier wait %lf ms, present %lf ms", &f.renderMs,
              &f.waitMs, &f.presentMs);
  return f;
}

std::string runJob(const std::string& command) {
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) throw Error("cannot start: " + command);
  std::string out;
  char buffer[4096];
  while (std::size_t n = std::fread(buffer, 1, sizeof buffer, pipe)) out.append(buffer, n);
  const int status = pclose(pipe);
  if (status != 0) throw Error("exit status " + std::to_string(status) + " of: " + command + "\n" + out);
  return out;
}

int run(const WallBenchOptions& o) {
  const fs::path dir = fs::temp_directory_path() / ("holotrace-bench-wall-" + std::to_string(getpid()));
  fs::create_directories(dir);
  std::ofstream(dir / "wall.json") << wallConfig(o);
  std::printf("wall: %u projectors of %ux%u, %u frames per job, %u jobs per rank count, swap timeout %u ms\n",
              o.projectors, o.viewWidth, o.viewHeight, o.frames, o.runs, o.swapTimeoutMs);
  std::printf("%5s %9s %14s %14s %14s %14s %10s %10s %10s\n", "ranks", "synced", "barrier_us", "release_skew_us",
              "flip_skew_us", "flip_skew_max", "render_ms", "wait_ms", "present_ms");
  for (const int ranks : o.ranks) {
    if (std::uint32_t(ranks) > o.projectors) throw UsageError("holotrace-bench-wall: more ranks than projectors");
    const std::uint32_t per = o.projectors / std::uint32_t(ranks);
    present::XvfbServer xvfb(o.viewWidth * o.projectors, o.viewHeight);
    std::string layout = "{\"ranks\": [";
    for (int r = 0; r < ranks; ++r) {
      const std::uint32_t first = std::uint32_t(r) * per;
      const std::uint32_t count = r + 1 == ranks ? o.projectors - first : per;
      xvfb.setMonitor("WALL-" + std::to_string(r),
                      {std::int32_t(first * o.viewWidth), 0, count * o.viewWidth, o.viewHeight}, {});
      layout += std::string(r ? ", " : "") + "{\"monitor\": \"WALL-" + std::to_string(r) +
                "\", \"projectors\": {\"first\": " + std::to_string(first) + ", \"count\": " + std::to_string(count) +
                "}}";
    }
    std::ofstream(dir / "layout.json") << layout << "]}";
    std::vector<RunFigures> runs;
    for (std::uint32_t i = 0; i < o.runs; ++i) {
      const std::string command =
          "OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 " + o.mpirun +
          " --oversubscribe --bind-to none --mca btl self,vader --mca btl_tcp_if_include lo --mca oob_tcp_if_include "
          "lo --mca btl_vader_single_copy_mechanism none --timeout 300 -np " +
          std::to_string(ranks) + " " + o.holotrace + " wall --display " + (dir / "wall.json").string() +
          " --scene builtin:showcase --layout " + (dir / "layout.json").string() + " --x-display " + xvfb.display() +
          " --frames " + std::to_string(o.frames) + " --swap-timeout " + std::to_string(o.swapTimeoutMs) + " 2>&1";
      runs.push_back(parseReport(runJob(command)));
    }
    const auto median = [&](double RunFigures::*field) {
      std::vector<double> v;
      for (const RunFigures& f : runs) v.push_back(f.*field);
      return cluster::medianOf(v);
    };
    std::vector<double> synced;
    for (const RunFigures& f : runs) synced.push_back(f.synced);
    std::printf("%5d %9.0f %14.1f %14.1f %14.1f %14.1f %10.2f %10.2f %10.2f\n", ranks, cluster::medianOf(synced),
                median(&RunFigures::costUs), median(&RunFigures::releaseUs), median(&RunFigures::flipUs),
                median(&RunFigures::flipMaxUs), median(&RunFigures::renderMs), median(&RunFigures::waitMs),
                median(&RunFigures::presentMs));
    std::fflush(stdout);
  }
  fs::remove_all(dir);
  return 0;
}

}  // namespace
}  // namespace ht::bench

int main(int argc, char** argv) {
  return ht::bench::benchMain(argc, argv, "holotrace-bench-wall", ht::bench::parse, ht::bench::run);
}
