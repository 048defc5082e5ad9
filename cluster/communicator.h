// communicator.h - the MPI job this process belongs to, as the few operations a cluster render needs. The only
// code that calls MPI is communicator_mpi.cpp; a build without MPI compiles communicator_none.cpp instead, whose
// join() throws. MPI errors come back as ClusterError (the communicator's error handler is MPI_ERRORS_RETURN), never
// as MPI's silent default abort.
#pragma once
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <vector>

namespace ht::cluster {

// A non-blocking reduction in flight (startMaxReduction()): test() polls it without blocking.
class PendingReduction {
 public:
  virtual ~PendingReduction() = default;
  // True once every rank has started its part and the result is here (then result() holds it).
  virtual bool test() = 0;
  virtual const std::vector<std::int64_t>& result() const = 0;
};

// A message waiting to be received (probe()).
struct Incoming {
  int source = 0;
  int tag = 0;
};

// Which threads call MPI (MPI 3.1 §12.4.3): Funneled = only the thread that joined; Serialized = any thread, one at a
// time (holotraced under mpirun: the render worker thread renders frames, the main thread starts and stops the job).
enum class ThreadUse { Funneled, Serialized };

class Communicator {
 public:
  // Initialises MPI (thread level FUNNELED or SERIALIZED; the joining thread must also destroy the communicator,
  // which finalises MPI) and sets MPI_ERRORS_RETURN on the world communicator. Throws ClusterError when MPI is
  // missing from this build or cannot start.
  static std::unique_ptr<Communicator> join(ThreadUse threads = ThreadUse::Funneled);
  // A job of one rank without MPI (communicator_solo.cpp): the same code then runs in a plain process.
  static std::unique_ptr<Communicator> solo();
  // join() when an MPI launcher started this process (mpi_launch.h), else solo().
  static std::unique_ptr<Communicator> forThisProcess();
  virtual ~Communicator() = default;  // finalises MPI unless the job was aborted

  virtual int rank() const = 0;
  virtual int size() const = 0;

  // Root's `bytes` on every rank (any size: sent as a 64-bit length, then chunks of at most 1 GiB).
  virtual void broadcast(std::vector<std::uint8_t>& bytes, int root) = 0;
  // Every rank's `mine` (all of the same size), concatenated in rank order, on every rank.
  virtual std::vector<std::uint8_t> allGather(std::span<const std::uint8_t> mine) = 0;
  virtual void barrier() = 0;
  // The element-wise maximum of every rank's `values` (all of the same length), without blocking: MPI_Iallreduce on
  // a duplicate of the world communicator of its own, so these never match the world's collectives. No rank's
  // reduction completes before every rank has started it: a barrier that carries data (the live wall's swap
  // barrier, cluster/swap_barrier.h). Every rank starts the same reductions in the same order.
  virtual std::unique_ptr<PendingReduction> startMaxReduction(std::span<const std::int64_t> values) = 0;

  // Point to point (chunks of at most 1 GiB; the receiver must know the size).
  virtual void send(int destination, int tag, std::span<const std::uint8_t> bytes) = 0;
  virtual void receive(int source, int tag, std::span<std::uint8_t> bytes) = 0;
  // A message of any source and tag waiting to be received, without blocking.
  virtual std::optional<Incoming> probe() = 0;

  // Ends every rank of the job with exit status `code` (MPI_Abort); does not return.
  [[noreturn]] virtual void abort(int code) = 0;
};

// Typed helpers over send/receive for fixed-size records.
template <typename T>
void sendRecord(Communicator& comm, int destination, int tag, const T& record) {
  comm.send(destination, tag, std::span(reinterpret_cast<const std::uint8_t*>(&record), sizeof(T)));
}
template <typename T>
T receiveRecord(Communicator& comm, int source, int tag) {
  T record{};
  comm.receive(source, tag, std::span(reinterpret_cast<std::uint8_t*>(&record), sizeof(T)));
  return record;
}

}  // namespace ht::cluster
