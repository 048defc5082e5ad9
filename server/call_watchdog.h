// call_watchdog.h - cancels calls that stopped making progress, so a stalled client frees its thread, its call slot
// and its memory (docs/SERVICE.md §5 "Stalled clients"): an UploadScene whose Read() waits longer than
// limits.upload_idle_seconds for the next chunk, a RenderFrame/StreamFrames/Capture whose Write() is held back by
// HTTP/2 flow control (a client that stopped reading) longer than limits.stream_stall_seconds. The synchronous gRPC
// API has no timeout on Read/Write; ServerContext::TryCancel() from another thread ends the blocked call, which then
// returns false.
#pragma once
#include <grpcpp/server_context.h>

#include <chrono>
#include <cstdint>
#include <mutex>
#include <ostream>
#include <set>
#include <string>

namespace ht::server {

class CallWatchdog {
 public:
  using Clock = std::chrono::steady_clock;

  explicit CallWatchdog(std::ostream& log) : log_(log) {}

  // One call under watch, registered for its lifetime. Wait marks one blocking Read/Write.
  class Watch {
   public:
    Watch(CallWatchdog& dog, grpc::ServerContext& context, double limitSeconds, std::string what);
    ~Watch();
    Watch(const Watch&) = delete;
    Watch& operator=(const Watch&) = delete;
    bool stalled() const;  // the watchdog cancelled this call

    class Wait {
     public:
      explicit Wait(Watch& watch);
      ~Wait();
      Wait(const Wait&) = delete;
      Wait& operator=(const Wait&) = delete;

     private:
      Watch& watch_;
    };

   private:
    friend class CallWatchdog;
    CallWatchdog& dog_;
    grpc::ServerContext& context_;
    const std::chrono::duration<double> limit_;
    const std::string what_;
    Clock::time_point waitingSince_{};  // epoch = not waiting; guarded by dog_.mutex_
    bool stalled_ = false;              // guarded by dog_.mutex_
  };

  // Cancels every call whose current wait is past its limit (the daemon's janitor calls it periodically).
  // Returns how many it cancelled.
  std::uint32_t check();
  std::uint64_t cancelledTotal() const;

 private:
  std::ostream& log_;
  mutable std::mutex mutex_;
  std::set<Watch*> watches_;
  std::uint64_t cancelled_ = 0;
};

}  // namespace ht::server
