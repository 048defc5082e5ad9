// soak_options.cpp - see soak_options.h.
#include "bench/soak_options.h"

#include <map>
#include <stdexcept>

namespace ht::bench {

const char* const kSoakUsage =
    "usage: holotrace-soak (--daemon PATH --displays-dir DIR | --socket ADDR [--output-root DIR]) [--seconds 1800]\n"
    "                      [--warmup-seconds S] [--clients 8] [--seed 1] [--sample-seconds 2] [--display ID]\n"
    "                      [--quiesce-seconds S] [--rss-tolerance-mib 24] [--samples-csv FILE] [--cycles N]\n"
    "                      [--mix all|load-render]\n"
    "  Mixed clients load, upload, stream, capture, cancel, stall and disconnect against holotraced for --seconds\n"
    "  after a warm-up; the daemon's RSS, threads and open fds are sampled through Status. At rest after the warm-up\n"
    "  and again after the run they must match (within the tolerances), and no call may fail unexpectedly; the\n"
    "  exit status is 0 only then (docs/SERVICE.md §10). --cycles N ends the run after N load/render cycles;\n"
    "  --mix load-render makes every action a short-lived load + render client.\n";

namespace {

double number(const std::string& option, const std::string& text) {
  try {
    std::size_t used = 0;
    const double value = std::stod(text, &used);
    if (used != text.size() || !(value >= 0)) throw std::invalid_argument("");
    return value;
  } catch (const std::exception&) {
    throw std::invalid_argument(option + ": '" + text + "' is not a non-negative number");
  }
}

void apply(SoakOptions& o, const std::string& key, const std::string& value) {
  const std::map<std::string, std::string*> texts = {
      {"--daemon", &o.daemonExe}, {"--socket", &o.socket},          {"--displays-dir", &o.displaysDir},
      {"--display", &o.display},  {"--output-root", &o.outputRoot}, {"--samples-csv", &o.samplesCsv}};
  if (auto it = texts.find(key); it != texts.end()) {
    *it->second = value;
  } else if (key == "--seconds") {
    o.seconds = number(key, value);
  } else if (key == "--warmup-seconds") {
    o.warmupSeconds = number(key, value);
  } else if (key == "--clients") {
    o.clients = static_cast<int>(number(key, value));
  } else if (key == "--seed") {
    o.seed = static_cast<std::uint64_t>(number(key, value));
  } else if (key == "--sample-seconds") {
    o.sampleSeconds = number(key, value);
  } else if (key == "--quiesce-seconds") {
    o.quiesceSeconds = number(key, value);
  } else if (key == "--cycles") {
    o.cycles = static_cast<std::uint64_t>(number(key, value));
  } else if (key == "--mix") {
    if (value != "all" && value != "load-render") throw std::invalid_argument("--mix must be all or load-render");
    o.loadRenderOnly = value == "load-render";
  } else if (key == "--rss-tolerance-mib") {
    o.rssToleranceKiB = static_cast<std::uint64_t>(number(key, value) * 1024);
  } else {
    throw std::invalid_argument("unknown option " + key);
  }
}

}  // namespace

SoakOptions parseSoakOptions(int argc, char** argv) {
  SoakOptions o;
  for (int i = 1; i < argc; i += 2) {
    if (i + 1 >= argc) throw std::invalid_argument(std::string(argv[i]) + " needs a value");
    apply(o, argv[i], argv[i + 1]);
  }
  if (o.daemonExe.empty() == o.socket.empty()) throw std::invalid_argument("give exactly one of --daemon, --socket");
  if (!o.daemonExe.empty() && o.displaysDir.empty()) throw std::invalid_argument("--daemon needs --displays-dir");
  if (o.clients < 1 || o.clients > 64) throw std::invalid_argument("--clients must be in [1, 64]");
  if (o.sampleSeconds < 0.1) throw std::invalid_argument("--sample-seconds must be >= 0.1");
  if (o.warmupSeconds == 0) o.warmupSeconds = std::max(5.0, o.seconds / 10);
  return o;
}

}  // namespace ht::bench
