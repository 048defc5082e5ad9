// work_dispatch.cpp - see work_dispatch.h.
#include "cluster/work_dispatch.h"

#include <chrono>
#include <csignal>
#include <cstdlib>
#include <exception>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <utility>

#include "cluster/cluster_error.h"

namespace ht::cluster {
namespace {

using Clock = std::chrono::steady_clock;

enum Tag : int { kReady = 101, kAssign = 102, kHeader = 103, kPixels = 104 };

struct ResultHeader {
  std::int64_t unit = -1;
  double busyMs = 0.0;
  std::uint64_t floats = 0;
};

double msSince(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

std::span<const std::uint8_t> bytesOf(const std::vector<float>& v) {
  return {reinterpret_cast<const std::uint8_t*>(v.data()), v.size() * sizeof(float)};
}

// The failure-test hook (kKillRankVariable).
void maybeDieAfterFirstUnit(int rank, std::uint32_t unitsDone) {
  const char* value = std::getenv(kKillRankVariable);
  if (value == nullptr || unitsDone != 1 || std::atoi(value) != rank) return;
  std::raise(SIGKILL);
}

// The units a rank takes: rank 0's dynamic counter (shared by its render thread and the requests it answers), or a
// fixed block.
class UnitSource {
 public:
  UnitSource(std::size_t units, int ranks, Assignment assignment)
      : units_(units), ranks_(ranks), assignment_(assignment) {}
  std::optional<std::size_t> next(int rank) {
    std::lock_guard lock(mutex_);
    if (cancelled_) return std::nullopt;
    if (assignment_ == Assignment::Dynamic) {
      if (next_ >= units_) return std::nullopt;
      return next_++;
    }
    std::size_t& at = cursor(rank);
    if (at >= units_ || staticOwner(at, units_, ranks_) != rank) return std::nullopt;
    return at++;
  }
  // No more units for anyone (rank 0 failed: its render thread stops after its current unit).
  void cancel() {
    std::lock_guard lock(mutex_);
    cancelled_ = true;
  }

 private:
  std::size_t& cursor(int rank) {
    if (cursors_.empty()) {
      cursors_.resize(static_cast<std::size_t>(ranks_), units_);
      for (std::size_t u = units_; u-- > 0;) cursors_[static_cast<std::size_t>(staticOwner(u, units_, ranks_))] = u;
    }
    return cursors_[static_cast<std::size_t>(rank)];
  }
  std::size_t units_;
  int ranks_;
  Assignment assignment_;
  std::size_t next_ = 0;
  bool cancelled_ = false;
  std::vector<std::size_t> cursors_;
  std::mutex mutex_;
};

// Rank 0's own rendering, on a second thread: results queue up for the main thread.
class LocalRenderer {
 public:
  LocalRenderer(std::span<const WorkUnit> units, const UnitRenderer& render, UnitSource& source)
      : source_(source), thread_([this, units, &render, &source] { run(units, render, source); }) {}
  // Normally every unit has been handed out by now; after a failure this stops the thread at its current unit.
  ~LocalRenderer() {
    source_.cancel();
    if (thread_.joinable()) thread_.join();
  }
  // Finished units since the last call; rethrows the thread's exception.
  std::vector<std::pair<std::size_t, std::vector<float>>> drain(RankWork& work) {
    std::lock_guard lock(mutex_);
    if (error_) std::rethrow_exception(error_);
    work = work_;
    return std::exchange(done_, {});
  }
  bool finished() {
    std::lock_guard lock(mutex_);
    return finished_ && done_.empty();
  }

 private:
  void run(std::span<const WorkUnit> units, const UnitRenderer& render, UnitSource& source) {
    try {
      while (const auto unit = source.next(0)) {
        const auto start = Clock::now();
        std::vector<float> rgba = render(units[*unit]);
        std::lock_guard lock(mutex_);
        work_.busyMs += msSince(start);
        ++work_.units;
        done_.emplace_back(*unit, std::move(rgba));
      }
    } catch (...) {
      std::lock_guard lock(mutex_);
      error_ = std::current_exception();
    }
    std::lock_guard lock(mutex_);
    finished_ = true;
  }
  std::mutex mutex_;
  std::vector<std::pair<std::size_t, std::vector<float>>> done_;
  RankWork work_;
  std::exception_ptr error_;
  bool finished_ = false;
  UnitSource& source_;
  std::thread thread_;
};

void coordinate(Communicator& comm, std::span<const WorkUnit> units, const UnitRenderer& render, const UnitSink& sink,
                Assignment assignment, DispatchReport& report) {
  UnitSource source(units.size(), comm.size(), assignment);
  const int askers = assignment == Assignment::Dynamic ? comm.size() - 1 : 0;
  std::size_t received = 0;
  int stopped = 0;
  const auto assign = [&](int rank) {
    const std::optional<std::size_t> unit = source.next(rank);
    sendRecord(comm, rank, kAssign, static_cast<std::int64_t>(unit ? static_cast<std::int64_t>(*unit) : -1));
    if (!unit) ++stopped;
  };
  LocalRenderer local(units, render, source);
  while (received < units.size() || stopped < askers) {
    for (auto& [unit, rgba] : local.drain(report.ranks[0])) {
      sink(unit, std::move(rgba));
      ++received;
    }
    const std::optional<Incoming> message = comm.probe();
    if (!message) {
      std::this_thread::sleep_for(std::chrono::microseconds(50));
      continue;
    }
    if (message->tag == kReady) {
      receiveRecord<std::int64_t>(comm, message->source, kReady);
      assign(message->source);
    } else if (message->tag == kHeader) {
      const auto header = receiveRecord<ResultHeader>(comm, message->source, kHeader);
      if (header.unit < 0 || static_cast<std::size_t>(header.unit) >= units.size()) {
        throw ClusterError("rank " + std::to_string(message->source) + " reported unknown work unit " +
                           std::to_string(header.unit));
      }
      std::vector<float> rgba(static_cast<std::size_t>(header.floats));
      const auto start = Clock::now();
      comm.receive(message->source, kPixels,
                   {reinterpret_cast<std::uint8_t*>(rgba.data()), rgba.size() * sizeof(float)});
      report.gatherMs += msSince(start);
      report.gatherBytes += rgba.size() * sizeof(float);
      RankWork& work = report.ranks[static_cast<std::size_t>(message->source)];
      work.busyMs += header.busyMs;
      ++work.units;
      sink(static_cast<std::size_t>(header.unit), std::move(rgba));
      ++received;
      if (assignment == Assignment::Dynamic) assign(message->source);
    } else {
      throw ClusterError("rank " + std::to_string(message->source) + " sent an unexpected message (tag " +
                         std::to_string(message->tag) + ")");
    }
  }
  while (!local.finished()) std::this_thread::sleep_for(std::chrono::microseconds(50));
  local.drain(report.ranks[0]);
}

void work(Communicator& comm, std::span<const WorkUnit> units, const UnitRenderer& render, Assignment assignment,
          DispatchReport& report) {
  UnitSource blocks(units.size(), comm.size(), assignment);
  RankWork& mine = report.ranks[static_cast<std::size_t>(comm.rank())];
  const auto nextUnit = [&]() -> std::optional<std::size_t> {
    if (assignment == Assignment::Static) return blocks.next(comm.rank());
    const auto unit = receiveRecord<std::int64_t>(comm, 0, kAssign);
    if (unit < 0) return std::nullopt;
    return static_cast<std::size_t>(unit);
  };
  if (assignment == Assignment::Dynamic) sendRecord(comm, 0, kReady, std::int64_t{0});
  while (const auto unit = nextUnit()) {
    if (*unit >= units.size()) throw ClusterError("rank 0 assigned unknown work unit " + std::to_string(*unit));
    const auto start = Clock::now();
    const std::vector<float> rgba = render(units[*unit]);
    const ResultHeader header{static_cast<std::int64_t>(*unit), msSince(start), rgba.size()};
    mine.busyMs += header.busyMs;
    ++mine.units;
    maybeDieAfterFirstUnit(comm.rank(), mine.units);
    sendRecord(comm, 0, kHeader, header);
    comm.send(0, kPixels, bytesOf(rgba));
  }
}

}  // namespace

DispatchReport dispatchWork(Communicator& comm, std::span<const WorkUnit> units, const UnitRenderer& render,
                            const UnitSink& sink, Assignment assignment) {
  const auto start = Clock::now();
  DispatchReport report;
  report.ranks.resize(static_cast<std::size_t>(comm.size()));
  if (comm.rank() == 0)
    coordinate(comm, units, render, sink, assignment, report);
  else
    work(comm, units, render, assignment, report);
  report.wallMs = msSince(start);
  return report;
}

}  // namespace ht::cluster
