// frame_mailbox.h - the one-slot "latest frame" between a renderer and a present thread. The renderer never waits:
// put() stores the frame and returns; a frame still in the slot is replaced and counted as dropped. The present
// thread takes the newest frame when it is ready for one. Thread-safe.
#pragma once
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>

#include "present/panel_frame.h"

namespace ht::present {

class FrameMailbox {
 public:
  using FramePtr = std::shared_ptr<const PanelFrame>;

  // Stores `frame` (its sequence is set here); returns the sequence. Never blocks on the taker.
  std::uint64_t put(PanelFrame frame);

  // The newest frame not yet taken, waiting up to `timeout` for one; nullptr on timeout or after close().
  FramePtr take(std::chrono::milliseconds timeout);

  // Wakes a waiting take() for good (shutdown).
  void close();

  std::uint64_t submitted() const;  // frames put
  std::uint64_t dropped() const;    // frames replaced before they were taken

 private:
  mutable std::mutex mutex_;
  std::condition_variable ready_;
  FramePtr slot_;
  std::uint64_t submitted_ = 0, dropped_ = 0;
  bool closed_ = false;
};

}  // namespace ht::present
