// communicator_mpi.cpp - Communicator over Open MPI (docs/CLUSTER.md §2). Every call's return code is checked: the
// world communicator returns errors (MPI_ERRORS_RETURN) and they become ClusterError naming the call. Large buffers
// go in chunks of at most 1 GiB, since MPI 3.1 counts are ints.
#include <mpi.h>

#include <algorithm>
#include <cstdlib>
#include <memory>
#include <string>

#include "cluster/cluster_error.h"
#include "cluster/communicator.h"

namespace ht::cluster {
namespace {

constexpr std::size_t kChunkBytes = std::size_t{1} << 30;

void check(int code, const char* call) {
  if (code == MPI_SUCCESS) return;
  char text[MPI_MAX_ERROR_STRING] = {};
  int length = 0;
  MPI_Error_string(code, text, &length);
  throw ClusterError(std::string(call) + " failed: " + std::string(text, static_cast<std::size_t>(length)));
}

int chunkCount(std::size_t bytes, std::size_t offset) {
  return static_cast<int>(std::min(kChunkBytes, bytes - offset));
}

// MPI_Iallreduce (MAX) in flight. MPI forbids freeing or cancelling the request of a non-blocking collective, and
// waiting for it could hang behind a rank that never comes: a reduction dropped while still pending (only on the way
// to MPI_Abort after an error) leaves its buffers to MPI on purpose.
class MpiReduction final : public PendingReduction {
 public:
  MpiReduction(MPI_Comm comm, std::span<const std::int64_t> values) : buffers_(std::make_unique<Buffers>()) {
    buffers_->values.assign(values.begin(), values.end());
    buffers_->result.resize(values.size());
    check(MPI_Iallreduce(buffers_->values.data(), buffers_->result.data(), static_cast<int>(values.size()), MPI_INT64_T,
                         MPI_MAX, comm, &request_),
          "MPI_Iallreduce");
  }
  ~MpiReduction() override {
    if (request_ != MPI_REQUEST_NULL) (void)buffers_.release();
  }
  MpiReduction(const MpiReduction&) = delete;
  MpiReduction& operator=(const MpiReduction&) = delete;

  bool test() override {
    if (request_ == MPI_REQUEST_NULL) return true;
    int done = 0;
    check(MPI_Test(&request_, &done, MPI_STATUS_IGNORE), "MPI_Test (MPI_Iallreduce)");
    return done != 0;
  }
  const std::vector<std::int64_t>& result() const override { return buffers_->result; }

 private:
  struct Buffers {
    std::vector<std::int64_t> values, result;
  };
  std::unique_ptr<Buffers> buffers_;
  MPI_Request request_ = MPI_REQUEST_NULL;
};

class MpiCommunicator final : public Communicator {
 public:
  explicit MpiCommunicator(ThreadUse threads) {
    const int wanted = threads == ThreadUse::Serialized ? MPI_THREAD_SERIALIZED : MPI_THREAD_FUNNELED;
    int provided = 0;
    check(MPI_Init_thread(nullptr, nullptr, wanted, &provided), "MPI_Init_thread");
    check(MPI_Comm_set_errhandler(MPI_COMM_WORLD, MPI_ERRORS_RETURN), "MPI_Comm_set_errhandler");
    if (provided < wanted) {
      throw ClusterError(std::string("MPI_Init_thread: the MPI library offers no ") +
                         (threads == ThreadUse::Serialized ? "MPI_THREAD_SERIALIZED" : "MPI_THREAD_FUNNELED") +
                         " support");
    }
    check(MPI_Comm_rank(MPI_COMM_WORLD, &rank_), "MPI_Comm_rank");
    check(MPI_Comm_size(MPI_COMM_WORLD, &size_), "MPI_Comm_size");
    check(MPI_Comm_dup(MPI_COMM_WORLD, &reductions_), "MPI_Comm_dup");
    check(MPI_Comm_set_errhandler(reductions_, MPI_ERRORS_RETURN), "MPI_Comm_set_errhandler");
  }
  ~MpiCommunicator() override {
    MPI_Comm_free(&reductions_);
    MPI_Finalize();
  }

  int rank() const override { return rank_; }
  int size() const override { return size_; }

  void broadcast(std::vector<std::uint8_t>& bytes, int root) override {
    std::uint64_t length = bytes.size();
    check(MPI_Bcast(&length, 1, MPI_UINT64_T, root, MPI_COMM_WORLD), "MPI_Bcast (length)");
    bytes.resize(static_cast<std::size_t>(length));
    for (std::size_t at = 0; at < bytes.size(); at += kChunkBytes) {
      check(MPI_Bcast(bytes.data() + at, chunkCount(bytes.size(), at), MPI_BYTE, root, MPI_COMM_WORLD), "MPI_Bcast");
    }
  }

  std::vector<std::uint8_t> allGather(std::span<const std::uint8_t> mine) override {
    std::vector<std::uint8_t> all(mine.size() * static_cast<std::size_t>(size_));
    check(MPI_Allgather(mine.data(), static_cast<int>(mine.size()), MPI_BYTE, all.data(), static_cast<int>(mine.size()),
                        MPI_BYTE, MPI_COMM_WORLD),
          "MPI_Allgather");
    return all;
  }

  void barrier() override { check(MPI_Barrier(MPI_COMM_WORLD), "MPI_Barrier"); }

  std::unique_ptr<PendingReduction> startMaxReduction(std::span<const std::int64_t> values) override {
    return std::make_unique<MpiReduction>(reductions_, values);
  }

  void send(int destination, int tag, std::span<const std::uint8_t> bytes) override {
    if (bytes.empty()) {
      check(MPI_Send(nullptr, 0, MPI_BYTE, destination, tag, MPI_COMM_WORLD), "MPI_Send");
      return;
    }
    for (std::size_t at = 0; at < bytes.size(); at += kChunkBytes) {
      check(MPI_Send(bytes.data() + at, chunkCount(bytes.size(), at), MPI_BYTE, destination, tag, MPI_COMM_WORLD),
            "MPI_Send");
    }
  }

  void receive(int source, int tag, std::span<std::uint8_t> bytes) override {
    if (bytes.empty()) {
      check(MPI_Recv(nullptr, 0, MPI_BYTE, source, tag, MPI_COMM_WORLD, MPI_STATUS_IGNORE), "MPI_Recv");
      return;
    }
    for (std::size_t at = 0; at < bytes.size(); at += kChunkBytes) {
      MPI_Status status;
      const int expected = chunkCount(bytes.size(), at);
      check(MPI_Recv(bytes.data() + at, expected, MPI_BYTE, source, tag, MPI_COMM_WORLD, &status), "MPI_Recv");
      int got = 0;
      check(MPI_Get_count(&status, MPI_BYTE, &got), "MPI_Get_count");
      if (got != expected) {
        throw ClusterError("rank " + std::to_string(source) + " sent " + std::to_string(got) + " bytes (tag " +
                           std::to_string(tag) + ") where " + std::to_string(expected) + " were expected");
      }
    }
  }

  std::optional<Incoming> probe() override {
    int flag = 0;
    MPI_Status status;
    check(MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &flag, &status), "MPI_Iprobe");
    if (!flag) return std::nullopt;
    return Incoming{status.MPI_SOURCE, status.MPI_TAG};
  }

  [[noreturn]] void abort(int code) override {
    MPI_Abort(MPI_COMM_WORLD, code);
    std::_Exit(code);  // MPI_Abort does not return; if a broken library did, still end this rank
  }

 private:
  int rank_ = 0, size_ = 1;
  MPI_Comm reductions_ = MPI_COMM_NULL;  // startMaxReduction's own communicator (a duplicate of the world)
};

}  // namespace

std::unique_ptr<Communicator> Communicator::join(ThreadUse threads) {
  return std::make_unique<MpiCommunicator>(threads);
}

}  // namespace ht::cluster
