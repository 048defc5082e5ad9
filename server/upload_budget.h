// upload_budget.h - bounds on UploadScene calls in flight (docs/SERVICE.md §5 "Stalled clients"): at most
// limits.max_uploads at once (each holds a gRPC thread while it waits for chunks), and at most
// limits.max_upload_bytes_in_flight declared bytes (info.total_bytes) among them, reserved before any byte is stored.
#pragma once
#include <cstdint>
#include <mutex>

namespace ht::server {

class UploadBudget {
 public:
  UploadBudget(std::uint32_t maxUploads, std::uint64_t maxBytes) : maxUploads_(maxUploads), maxBytes_(maxBytes) {}

  // One upload for its lifetime; throws LimitExceeded when limits.max_uploads are running.
  class Slot {
   public:
    explicit Slot(UploadBudget& budget);
    ~Slot();
    Slot(const Slot&) = delete;
    Slot& operator=(const Slot&) = delete;
    // Reserves the upload's declared size; throws LimitExceeded past limits.max_upload_bytes_in_flight.
    void reserve(std::uint64_t bytes);

   private:
    UploadBudget& budget_;
    std::uint64_t reserved_ = 0;
  };

  std::uint32_t uploads() const;
  std::uint64_t bytes() const;

 private:
  const std::uint32_t maxUploads_;
  const std::uint64_t maxBytes_;
  mutable std::mutex mutex_;
  std::uint32_t uploads_ = 0;
  std::uint64_t bytes_ = 0;
};

}  // namespace ht::server
