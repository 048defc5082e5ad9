// communicator_solo.cpp - the Communicator of a plain process: one rank, collectives return its own data, and
// point-to-point messages (which need a peer) never occur.
#include <cstdlib>

#include "cluster/cluster_error.h"
#include "cluster/communicator.h"
#include "cluster/mpi_launch.h"

namespace ht::cluster {
namespace {

// With one rank a reduction is complete at once: its result is the rank's own values.
class SoloReduction final : public PendingReduction {
 public:
  explicit SoloReduction(std::span<const std::int64_t> values) : values_(values.begin(), values.end()) {}
  bool test() override { return true; }
  const std::vector<std::int64_t>& result() const override { return values_; }

 private:
  std::vector<std::int64_t> values_;
};

class SoloCommunicator final : public Communicator {
 public:
  int rank() const override { return 0; }
  int size() const override { return 1; }
  void broadcast(std::vector<std::uint8_t>&, int) override {}
  std::vector<std::uint8_t> allGather(std::span<const std::uint8_t> mine) override {
    return {mine.begin(), mine.end()};
  }
  void barrier() override {}
  std::unique_ptr<PendingReduction> startMaxReduction(std::span<const std::int64_t> values) override {
    return std::make_unique<SoloReduction>(values);
  }
  void send(int destination, int, std::span<const std::uint8_t>) override { noPeer(destination); }
  void receive(int source, int, std::span<std::uint8_t>) override { noPeer(source); }
  std::optional<Incoming> probe() override { return std::nullopt; }
  [[noreturn]] void abort(int code) override { std::_Exit(code); }

 private:
  [[noreturn]] static void noPeer(int rank) {
    throw ClusterError("no rank " + std::to_string(rank) + " in a one-process job");
  }
};

}  // namespace

std::unique_ptr<Communicator> Communicator::solo() { return std::make_unique<SoloCommunicator>(); }

std::unique_ptr<Communicator> Communicator::forThisProcess() {
  if (launcherWorldSize()) return join();
  return solo();
}

}  // namespace ht::cluster
