// upload_budget.cpp - see upload_budget.h.
#include "server/upload_budget.h"

#include <string>

#include "server/errors.h"

namespace ht::server {

UploadBudget::Slot::Slot(UploadBudget& budget) : budget_(budget) {
  std::lock_guard lock(budget_.mutex_);
  if (budget_.uploads_ >= budget_.maxUploads_) {
    throw LimitExceeded("all " + std::to_string(budget_.maxUploads_) + " upload slots are busy (limits.max_uploads)");
  }
  ++budget_.uploads_;
}

UploadBudget::Slot::~Slot() {
  std::lock_guard lock(budget_.mutex_);
  --budget_.uploads_;
  budget_.bytes_ -= reserved_;
}

void UploadBudget::Slot::reserve(std::uint64_t bytes) {
  std::lock_guard lock(budget_.mutex_);
  if (bytes > budget_.maxBytes_ - budget_.bytes_) {
    throw LimitExceeded("upload of " + std::to_string(bytes) + " bytes: " + std::to_string(budget_.bytes_) +
                        " bytes of other uploads are in flight (limits.max_upload_bytes_in_flight = " +
                        std::to_string(budget_.maxBytes_) + ")");
  }
  budget_.bytes_ += bytes;
  reserved_ += bytes;
}

std::uint32_t UploadBudget::uploads() const {
  std::lock_guard lock(mutex_);
  return uploads_;
}

std::uint64_t UploadBudget::bytes() const {
  std::lock_guard lock(mutex_);
  return bytes_;
}

}  // namespace ht::server
