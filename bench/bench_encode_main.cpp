// bench_encode_main.cpp - holotrace-bench-encode: the cost of turning a rendered frame (linear float RGBA) into the
// bytes a client or the panel gets, at a panel's size: RGBA8 through the code tables (frame_io/code8_table.h, the
// path every RGBA8 stream frame and every frame the display sink shows takes), the same on one thread, the per-value
// sRGB function the tables replaced (one powf per colour value), and RGBA16F. Values are a fixed pseudo-random frame
// in [-0.1, 1.3) (the encoders clamp; the tables do not branch on the value). Each line: the median of --runs runs
// after one warm-up, and its ratio to the per-value function measured in the same runs; the bytes of every encoder
// are checked against the per-value function's.
//
// Usage: holotrace-bench-encode [--width 1536] [--height 2048] [--runs 7]
#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <random>
#include <span>
#include <string>
#include <thread>
#include <vector>

#include "bench/bench_main.h"
#include "bench/timing_series.h"
#include "cli/arguments.h"
#include "common/error.h"
#include "frame_io/pixel_encoding.h"

namespace ht::bench {
namespace {

const char* const kCommand = "holotrace-bench-encode";

struct EncodeOptions {
  std::uint32_t width = 1536, height = 2048, runs = 7;
};

const std::array<cli::OptionSpec, 3> kSpecs = {{
    {"--width", "", "N", "image width in pixels (default 1536, the Looking Glass Portrait's panel)"},
    {"--height", "", "N", "image height in pixels (default 2048)"},
    {"--runs", "", "N", "timed runs after one warm-up (default 7)"},
}};

std::optional<EncodeOptions> parseOptions(std::span<const std::string> args, std::string* help) {
  if (cli::wantsHelp(args)) {
    *help = std::string("Usage: ") + kCommand + " [options]\n\n" +
            "Times encoding one rendered frame as RGBA8 (sRGB) and RGBA16F bytes.\n\nOptions:\n" +
            cli::formatOptions(kSpecs);
    return std::nullopt;
  }
  const cli::ParsedArguments parsed = cli::parseArguments(kCommand, kSpecs, args);
  EncodeOptions o;
  o.width = parsed.unsignedValue("--width", 1, 16384).value_or(o.width);
  o.height = parsed.unsignedValue("--height", 1, 16384).value_or(o.height);
  o.runs = parsed.unsignedValue("--runs", 1, 1000).value_or(o.runs);
  return o;
}

// What encodeRgba8Srgb computed before the tables: one sRGB function call per colour value.
void encodePerValue(std::span<const float> rgba, std::span<std::uint8_t> out) {
  for (std::size_t i = 0; i < rgba.size(); ++i) {
    out[i] = i % 4 == 3 ? frame_io::linearEncode8(rgba[i]) : frame_io::srgbEncode8(rgba[i]);
  }
}

// The tables on the calling thread alone: slices below the size encodeRgba8Srgb cuts across threads.
void encodeOneThread(std::span<const float> rgba, std::span<std::uint8_t> out) {
  constexpr std::size_t kSlice = 4 * 100'000;
  for (std::size_t i = 0; i < rgba.size(); i += kSlice) {
    const std::size_t n = std::min(kSlice, rgba.size() - i);
    frame_io::encodeRgba8Srgb(rgba.subspan(i, n), out.subspan(i, n));
  }
}

double msOf(const auto& work) {
  const auto start = std::chrono::steady_clock::now();
  work();
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

int run(const EncodeOptions& o) {
  const std::size_t floats = std::size_t{o.width} * o.height * 4;
  std::vector<float> rgba(floats);
  std::mt19937 rng(1);
  std::uniform_real_distribution<float> value(-0.1f, 1.3f);
  for (float& v : rgba) v = value(rng);
  std::vector<std::uint8_t> reference(floats), tables(floats), oneThread(floats), half(2 * floats);
  TimingSeries perValue, table, single, rgba16f;
  std::vector<double> tableRatio, singleRatio;
  for (std::uint32_t r = 0; r <= o.runs; ++r) {  // run 0 warms up (and builds the tables)
    const double p = msOf([&] { encodePerValue(rgba, reference); });
    const double t = msOf([&] { frame_io::encodeRgba8Srgb(rgba, tables); });
    const double s = msOf([&] { encodeOneThread(rgba, oneThread); });
    const double h = msOf([&] { half = frame_io::encodeRgba16fLinear(rgba); });
    if (tables != reference || oneThread != reference) throw Error("the tables' bytes differ from the per-value codes");
    if (r == 0) continue;
    perValue.ms.push_back(p);
    table.ms.push_back(t);
    single.ms.push_back(s);
    rgba16f.ms.push_back(h);
    tableRatio.push_back(t / p);
    singleRatio.push_back(s / p);
  }
  std::printf("%s: %ux%u RGBA (%zu floats), medians of %u runs, %u hardware threads\n", kCommand, o.width, o.height,
              floats, o.runs, std::thread::hardware_concurrency());
  std::printf("  RGBA8, per-value sRGB function (before):  %8.2f ms\n", perValue.medianMs());
  std::printf("  RGBA8, code tables, threads (now):        %8.2f ms   ratio %.3f\n", table.medianMs(),
              median(tableRatio));
  std::printf("  RGBA8, code tables, one thread:           %8.2f ms   ratio %.3f\n", single.medianMs(),
              median(singleRatio));
  std::printf("  RGBA16F (half floats, new buffer):        %8.2f ms\n", rgba16f.medianMs());
  std::printf("  bytes: the tables' equal the per-value codes in every run\n");
  return 0;
}

}  // namespace
}  // namespace ht::bench

int main(int argc, char** argv) {
  return ht::bench::benchMain(argc, argv, ht::bench::kCommand, ht::bench::parseOptions, ht::bench::run);
}
