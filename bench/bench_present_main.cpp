// bench_present_main.cpp - holotrace-bench-present: the display sink (present/) on a private Xvfb (or --x-display):
//   1. present cost per frame: SwapchainPresenter::present back to back (staging upload + copy + vkQueuePresentKHR),
//      MAILBOX and FIFO, mean per frame of --frames presents; median/min/max of --runs runs;
//   2. render-to-photon latency: a frame marked done and submitted to an idle PanelSink -> vkQueuePresentKHR returned
//      in the present thread (PanelSinkStats::lastPresentLatencyMs); median of --frames frames per run, median of runs;
//   3. drops at 1x, 2x and 4x the sink's present rate measured in the same phase: frames (copied as a renderer would
//      hand them over) are submitted on a clock for --drop-seconds at factor x the rate the sink is presenting at
//      under that very load: the rate starts from a closed-loop estimate (one frame in flight) and is re-measured
//      every 250 ms from the frames presented in the last 500 ms of the window. (Taking the rate from a separate
//      phase fails on a loaded machine: the submitter's own copies slow the sink, so "1x" overran it and 54 % were
//      dropped.) Printed: dropped / submitted, the sink's presented rate over the window, median of runs;
//   4. resident memory (VmRSS) of this process over --rss-frames presented frames, sampled every 1000.
// Frames are random bytes of the panel size (the present path does not look at content); no rendering is involved.
//
// Usage: holotrace-bench-present [--width 1536] [--height 2048] [--runs 5] [--frames 30] [--drop-seconds 2]
//                                [--rss-frames 10000] [--x-display :N]
#include <cstdio>
#include <fstream>
#include <iostream>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "bench/bench_main.h"
#include "bench/timing_series.h"
#include "cli/arguments.h"
#include "gpu/vulkan_context.h"
#include "present/edid.h"
#include "present/panel_sink.h"
#include "present/randr_reader.h"
#include "present/swapchain_presenter.h"
#include "present/x_window.h"
#include "present/xvfb_server.h"

namespace ht::bench {
namespace {

using present::Clock;

struct PresentBenchOptions {
  std::uint32_t width = 1536, height = 2048;
  std::uint32_t runs = 5, frames = 30, dropSeconds = 2, rssFrames = 10000;
  std::string xDisplay;  // "" = a private Xvfb of the panel's size
};

const std::vector<cli::OptionSpec> kSpecs = {
    {"--width", "", "N", "panel width in pixels (default 1536, the Portrait)"},
    {"--height", "", "N", "panel height in pixels (default 2048)"},
    {"--runs", "", "N", "runs per figure, median reported (default 5)"},
    {"--frames", "", "N", "presents per cost/latency run (default 30)"},
    {"--drop-seconds", "", "N", "seconds per drop-rate run (default 2)"},
    {"--rss-frames", "", "N", "presented frames of the memory series (default 10000; 0 = skip)"},
    {"--x-display", "", "NAME", "present on this X server's LKG/size-matching monitor instead of a private Xvfb"},
};

std::optional<PresentBenchOptions> parse(const std::vector<std::string>& args, std::string* help) {
  if (cli::wantsHelp(args)) {
    *help = "holotrace-bench-present: the display sink's cost, latency, drops and memory (docs/BENCHMARKS.md)\n\n" +
            cli::formatOptions(kSpecs);
    return std::nullopt;
  }
  const cli::ParsedArguments p = cli::parseArguments("holotrace-bench-present", kSpecs, args);
  PresentBenchOptions o;
  o.width = p.unsignedValue("--width", 16, 8192).value_or(o.width);
  o.height = p.unsignedValue("--height", 16, 8192).value_or(o.height);
  o.runs = p.unsignedValue("--runs", 1, 1000).value_or(o.runs);
  o.frames = p.unsignedValue("--frames", 2, 100000).value_or(o.frames);
  o.dropSeconds = p.unsignedValue("--drop-seconds", 1, 3600).value_or(o.dropSeconds);
  o.rssFrames = p.unsignedValue("--rss-frames", 0, 10'000'000).value_or(o.rssFrames);
  o.xDisplay = p.textOr("--x-display", "");
  return o;
}

std::vector<present::PanelFrame> noiseFrames(const PresentBenchOptions& o, std::size_t count) {
  std::mt19937 rng(7);
  std::vector<present::PanelFrame> frames(count);
  for (present::PanelFrame& f : frames) {
    f.width = o.width;
    f.height = o.height;
    f.rgba.resize(std::size_t(o.width) * o.height * 4);
    for (std::uint8_t& b : f.rgba) b = static_cast<std::uint8_t>(rng());
  }
  return frames;
}

double msBetween(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double, std::milli>(b - a).count();
}

std::uint64_t residentKiB() {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line)) {
    if (line.rfind("VmRSS:", 0) == 0) return std::stoull(line.substr(6));
  }
  return 0;
}

void printSeries(const char* what, const std::vector<double>& values, const char* unit) {
  const auto [lo, hi] = std::minmax_element(values.begin(), values.end());
  std::printf("%-44s median %8.2f %s  (min %.2f, max %.2f, %zu runs)\n", what, median(values), unit, *lo, *hi,
              values.size());
}

// 1. present() back to back in this thread: mean ms per frame of each run.
std::vector<double> presentCost(const PresentBenchOptions& o, const std::string& display, const present::Rect& rect,
                                present::PresentModeChoice mode, const std::vector<present::PanelFrame>& frames,
                                std::string* modeName) {
  gpu::VulkanContext context({-1, false, true});
  present::XConnection x(display);
  present::XWindow window(x, rect, present::WindowMode::OverrideRedirect);
  present::SwapchainPresenter presenter(context, x, window.id(), mode);
  *modeName = presenter.info().presentMode;
  for (int i = 0; i < 3; ++i) presenter.present(frames[i % frames.size()]);  // warm-up
  std::vector<double> perFrame;
  for (std::uint32_t run = 0; run < o.runs; ++run) {
    const auto start = Clock::now();
    for (std::uint32_t i = 0; i < o.frames; ++i) presenter.present(frames[i % frames.size()]);
    perFrame.push_back(msBetween(start, Clock::now()) / o.frames);
  }
  return perFrame;
}

present::PanelSinkOptions sinkOptions(const PresentBenchOptions& o, const std::string& display) {
  present::PanelSinkOptions s;
  s.xDisplay = display;
  s.panel = present::PanelRequest{o.width, o.height, std::nullopt, std::nullopt};
  return s;
}

void waitAttached(const present::PanelSink& sink) {
  const auto deadline = Clock::now() + std::chrono::seconds(30);
  while (!sink.stats().attached && Clock::now() < deadline) std::this_thread::sleep_for(std::chrono::milliseconds(5));
  if (!sink.stats().attached) throw present::PresentError("the panel sink did not attach: " + sink.stats().lastError);
}

// Submits `frame` and waits until the sink has presented it; returns the stats then.
present::PanelSinkStats submitAndWait(present::PanelSink& sink, present::PanelFrame frame) {
  frame.done = Clock::now();
  const std::uint64_t seq = sink.submit(std::move(frame));
  present::PanelSinkStats s = sink.stats();
  while (s.lastPresentedSequence < seq) {
    std::this_thread::sleep_for(std::chrono::microseconds(200));
    s = sink.stats();
  }
  return s;
}

// 2. Latency: one frame at a time to an idle sink.
std::vector<double> photonLatency(const PresentBenchOptions& o, present::PanelSink& sink,
                                  const std::vector<present::PanelFrame>& frames) {
  std::vector<double> perRun;
  for (std::uint32_t run = 0; run < o.runs; ++run) {
    std::vector<double> ms;
    for (std::uint32_t i = 0; i < o.frames; ++i) {
      ms.push_back(submitAndWait(sink, frames[i % frames.size()]).lastPresentLatencyMs);
      std::this_thread::sleep_for(std::chrono::milliseconds(5));  // idle sink: the next frame waits for nothing
    }
    perRun.push_back(median(ms));
  }
  return perRun;
}

// 3. The sink's present rate with one frame in flight, closed loop (frames/s), under the submitter's own load.
double closedLoopRate(const PresentBenchOptions& o, present::PanelSink& sink,
                      const std::vector<present::PanelFrame>& frames) {
  const auto start = Clock::now();
  for (std::uint32_t i = 0; i < o.frames; ++i) submitAndWait(sink, frames[i % frames.size()]);
  return 1000.0 * o.frames / msBetween(start, Clock::now());
}

struct DropRun {
  double startRate = 0.0;      // the closed-loop estimate the window starts from
  double dropPercent = 0.0;    // dropped / submitted in the window
  double presentedRate = 0.0;  // frames/s the sink presented during the window (the 1x it was fed against)
};

// Frames at `factor` x the sink's current present rate for --drop-seconds; the rate follows what the sink presents
// under this load (re-measured every 250 ms over the last 500 ms).
DropRun dropRun(const PresentBenchOptions& o, present::PanelSink& sink, double factor,
                const std::vector<present::PanelFrame>& frames) {
  DropRun r;
  r.startRate = closedLoopRate(o, sink, frames);
  double rate = r.startRate;
  const present::PanelSinkStats before = sink.stats();
  const auto start = Clock::now();
  struct Sample {
    Clock::time_point at;
    std::uint64_t presented;
  };
  std::vector<Sample> samples{{start, before.presented}};
  auto nextSubmit = start, nextEstimate = start + std::chrono::milliseconds(250);
  std::uint64_t k = 0;
  while (Clock::now() - start < std::chrono::seconds(o.dropSeconds)) {
    present::PanelFrame f = frames[k++ % frames.size()];  // the copy a renderer would hand over
    f.done = Clock::now();
    sink.submit(std::move(f));
    if (Clock::now() >= nextEstimate) {
      samples.push_back({Clock::now(), sink.stats().presented});
      std::size_t from = samples.size() - 1;
      while (from > 0 && samples.back().at - samples[from - 1].at <= std::chrono::milliseconds(500)) --from;
      const double seconds = msBetween(samples[from].at, samples.back().at) / 1000.0;
      const double presented = double(samples.back().presented - samples[from].presented);
      if (seconds > 0.0 && presented > 0.0) rate = presented / seconds;
      nextEstimate += std::chrono::milliseconds(250);
    }
    nextSubmit += std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(1.0 / (factor * rate)));
    std::this_thread::sleep_until(nextSubmit);
  }
  const double seconds = msBetween(start, Clock::now()) / 1000.0;
  const present::PanelSinkStats atEnd = sink.stats();
  std::this_thread::sleep_for(std::chrono::milliseconds(200));  // let the last frame be shown (not a drop)
  const present::PanelSinkStats after = sink.stats();
  const double submitted = double(after.submitted - before.submitted);
  r.dropPercent = submitted > 0 ? 100.0 * double(after.dropped - before.dropped) / submitted : 0.0;
  r.presentedRate = double(atEnd.presented - before.presented) / seconds;
  return r;
}

void printDrops(const PresentBenchOptions& o, present::PanelSink& sink,
                const std::vector<present::PanelFrame>& frames) {
  for (double factor : {1.0, 2.0, 4.0}) {
    std::vector<double> rate, drops, presented;
    for (std::uint32_t run = 0; run < o.runs; ++run) {
      const DropRun r = dropRun(o, sink, factor, frames);
      rate.push_back(r.startRate);
      drops.push_back(r.dropPercent);
      presented.push_back(r.presentedRate);
    }
    char what[96];
    std::snprintf(what, sizeof what, "dropped at %.0fx the same-phase present rate", factor);
    printSeries(what, drops, "%");
    printSeries("  sink presented during the window (frames/s)", presented, "");
    printSeries("  closed-loop start estimate (frames/s)", rate, "");
  }
}

// 4. VmRSS every 1000 presented frames, one frame in flight.
void rssSeries(const PresentBenchOptions& o, present::PanelSink& sink, const std::vector<present::PanelFrame>& frames) {
  if (o.rssFrames == 0) return;
  std::printf("VmRSS over %u presented frames (KiB, every 1000):", o.rssFrames);
  const std::uint64_t start = sink.stats().presented;
  std::uint64_t first = residentKiB(), last = first, peak = first;
  std::printf(" %llu", static_cast<unsigned long long>(first));
  const auto t0 = Clock::now();
  for (std::uint32_t i = 1; i <= o.rssFrames; ++i) {
    submitAndWait(sink, frames[i % frames.size()]);
    if (i % 1000 == 0) {
      last = residentKiB();
      peak = std::max(peak, last);
      std::printf(" %llu", static_cast<unsigned long long>(last));
      std::fflush(stdout);
    }
  }
  std::printf("\n  first %llu, last %llu, peak %llu KiB, %.1f s, presented %llu\n",
              static_cast<unsigned long long>(first), static_cast<unsigned long long>(last),
              static_cast<unsigned long long>(peak), msBetween(t0, Clock::now()) / 1000.0,
              static_cast<unsigned long long>(sink.stats().presented - start));
}

int run(const PresentBenchOptions& o) {
  std::unique_ptr<present::XvfbServer> xvfb;
  std::string display = o.xDisplay;
  if (display.empty()) {
    xvfb = std::make_unique<present::XvfbServer>(o.width, o.height);
    xvfb->setEdid("screen", present::makeEdid("LKG-P0001"));
    xvfb->setMonitor("LKG-P", {0, 0, o.width, o.height}, {"screen"});
    display = xvfb->display();
  }
  present::XConnection probe(display);
  const present::PickedMonitor monitor =
      present::pickMonitor(present::readRandrSnapshot(probe), {o.width, o.height, std::nullopt, std::nullopt});
  std::printf("panel %ux%u on X display %s, monitor %s %s; %u runs\n", o.width, o.height, display.c_str(),
              monitor.monitor.c_str(), present::describeRect(monitor.rect).c_str(), o.runs);
  const std::vector<present::PanelFrame> frames = noiseFrames(o, 4);

  std::string mailboxName, fifoName;
  const auto mailbox = presentCost(o, display, monitor.rect, present::PresentModeChoice::Auto, frames, &mailboxName);
  printSeries(("present cost per frame, " + mailboxName).c_str(), mailbox, "ms");
  const auto fifo = presentCost(o, display, monitor.rect, present::PresentModeChoice::Fifo, frames, &fifoName);
  printSeries(("present cost per frame, " + fifoName).c_str(), fifo, "ms");

  present::PanelSink sink(sinkOptions(o, display));
  waitAttached(sink);
  submitAndWait(sink, frames[0]);  // warm-up
  printSeries("render-to-photon latency (done -> presented)", photonLatency(o, sink, frames), "ms");
  printDrops(o, sink, frames);
  rssSeries(o, sink, frames);
  return 0;
}

}  // namespace
}  // namespace ht::bench

int main(int argc, char** argv) {
  return ht::bench::benchMain(argc, argv, "holotrace-bench-present", ht::bench::parse, ht::bench::run);
}
