// frame_mailbox.cpp - one slot, newest wins, drops counted.
#include "present/frame_mailbox.h"

#include <utility>

namespace ht::present {

std::uint64_t FrameMailbox::put(PanelFrame frame) {
  std::uint64_t sequence;
  {
    std::lock_guard lock(mutex_);
    sequence = ++submitted_;
    frame.sequence = sequence;
    if (frame.done == Clock::time_point{}) frame.done = Clock::now();
    if (slot_) ++dropped_;
    slot_ = std::make_shared<const PanelFrame>(std::move(frame));
  }
  ready_.notify_one();
  return sequence;
}

FrameMailbox::FramePtr FrameMailbox::take(std::chrono::milliseconds timeout) {
  std::unique_lock lock(mutex_);
  ready_.wait_for(lock, timeout, [&] { return slot_ != nullptr || closed_; });
  if (closed_) return nullptr;
  return std::exchange(slot_, nullptr);
}

void FrameMailbox::close() {
  {
    std::lock_guard lock(mutex_);
    closed_ = true;
  }
  ready_.notify_all();
}

std::uint64_t FrameMailbox::submitted() const {
  std::lock_guard lock(mutex_);
  return submitted_;
}

std::uint64_t FrameMailbox::dropped() const {
  std::lock_guard lock(mutex_);
  return dropped_;
}

}  // namespace ht::present
