// soak_client.h - the soak program's clients: each worker repeats randomly chosen actions of real clients, every
// action on a new connection (a short-lived client): load + render (+ unload or not), upload + render, stream and
// cancel or vanish, capture (sometimes cancelled), an upload that stalls, a stream whose reader pauses, status.
#pragma once
#include <atomic>
#include <cstdint>
#include <filesystem>
#include <map>
#include <mutex>
#include <string>

namespace ht::bench {

struct SoakTarget {
  std::string address;
  std::string display;
  std::filesystem::path outputRoot;  // captures are removed from here ("" = captures are skipped)
  bool hasGridScenes = false;        // scene root holds grid0..5.obj (a spawned daemon)
  bool loadRenderOnly = false;       // every action is loadRender
};

// Outcomes of all workers' calls.
class SoakTally {
 public:
  void count(const std::string& action, int grpcCode, const std::string& message);
  std::uint64_t failures() const;
  std::uint64_t loadRenderCycles() const { return cycles_.load(); }
  void addCycle() { ++cycles_; }
  std::string report() const;  // "action: N ok, N cancelled, ..." lines, then the first failures

 private:
  mutable std::mutex mutex_;
  std::map<std::string, std::map<int, std::uint64_t>> counts_;
  std::map<std::string, std::string> firstFailure_;
  std::atomic<std::uint64_t> cycles_{0};
};

// Runs actions until `stop` is set; `seed` makes the sequence reproducible.
void runSoakWorker(const SoakTarget& target, std::uint64_t seed, int worker, const std::atomic<bool>& stop,
                   SoakTally& tally);

}  // namespace ht::bench
