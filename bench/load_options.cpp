// load_options.cpp - see load_options.h.
#include "bench/load_options.h"

#include <stdexcept>

namespace ht::bench {

const char* const kLoadUsage =
    "usage: holotrace-bench-load --socket ADDR [--clients 8] [--seconds 10] [--frames N] [--fps 30]\n"
    "                            [--reconnect-every N] [--display ID] [--scene SPEC] [--spp 1] [--sample-ms 500]\n"
    "                            [--baseline-frames N --displays-dir DIR] [--samples-csv FILE]\n"
    "  Streams frames from holotraced on N connections until --seconds or --frames (total) is reached; samples the\n"
    "  daemon's RSS and CPU time through Status; --baseline-frames renders the same frames in-process first.\n";

namespace {

template <typename T>
T number(const std::string& option, const std::string& text) {
  try {
    std::size_t used = 0;
    const double value = std::stod(text, &used);
    if (used != text.size() || value < 0) throw std::invalid_argument("");
    return static_cast<T>(value);
  } catch (const std::exception&) {
    throw std::invalid_argument(option + ": '" + text + "' is not a non-negative number");
  }
}

void apply(LoadOptions& o, const std::string& key, const std::string& value) {
  if (key == "--socket")
    o.socket = value;
  else if (key == "--clients")
    o.clients = number<int>(key, value);
  else if (key == "--seconds")
    o.seconds = number<double>(key, value);
  else if (key == "--frames")
    o.frames = number<std::uint64_t>(key, value);
  else if (key == "--fps")
    o.fps = number<double>(key, value);
  else if (key == "--reconnect-every")
    o.reconnectEvery = number<std::uint64_t>(key, value);
  else if (key == "--display")
    o.display = value;
  else if (key == "--scene")
    o.scene = value;
  else if (key == "--spp")
    o.spp = number<std::uint32_t>(key, value);
  else if (key == "--sample-ms")
    o.sampleMs = number<int>(key, value);
  else if (key == "--baseline-frames")
    o.baselineFrames = number<std::uint64_t>(key, value);
  else if (key == "--displays-dir")
    o.displaysDir = value;
  else if (key == "--samples-csv")
    o.samplesCsv = value;
  else
    throw std::invalid_argument("unknown option " + key);
}

}  // namespace

LoadOptions parseLoadOptions(int argc, char** argv) {
  LoadOptions o;
  for (int i = 1; i < argc; i += 2) {
    if (i + 1 >= argc) throw std::invalid_argument(std::string(argv[i]) + " needs a value");
    apply(o, argv[i], argv[i + 1]);
  }
  if (o.seconds == 0 && o.frames == 0) o.seconds = 10.0;
  if (o.socket.empty()) throw std::invalid_argument("--socket is required");
  if (o.clients < 1) throw std::invalid_argument("--clients must be >= 1");
  if (o.sampleMs < 10) throw std::invalid_argument("--sample-ms must be >= 10");
  if (!(o.fps > 0)) throw std::invalid_argument("--fps must be > 0");
  return o;
}

}  // namespace ht::bench
