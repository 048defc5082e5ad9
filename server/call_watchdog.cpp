// call_watchdog.cpp - see call_watchdog.h.
#include "server/call_watchdog.h"

namespace ht::server {

CallWatchdog::Watch::Watch(CallWatchdog& dog, grpc::ServerContext& context, double limitSeconds, std::string what)
    : dog_(dog), context_(context), limit_(limitSeconds), what_(std::move(what)) {
  std::lock_guard lock(dog_.mutex_);
  dog_.watches_.insert(this);
}

CallWatchdog::Watch::~Watch() {
  std::lock_guard lock(dog_.mutex_);  // after this, check() never touches the call's context again
  dog_.watches_.erase(this);
}

bool CallWatchdog::Watch::stalled() const {
  std::lock_guard lock(dog_.mutex_);
  return stalled_;
}

CallWatchdog::Watch::Wait::Wait(Watch& watch) : watch_(watch) {
  std::lock_guard lock(watch_.dog_.mutex_);
  watch_.waitingSince_ = Clock::now();
}

CallWatchdog::Watch::Wait::~Wait() {
  std::lock_guard lock(watch_.dog_.mutex_);
  watch_.waitingSince_ = {};
}

std::uint32_t CallWatchdog::check() {
  std::lock_guard lock(mutex_);
  const auto now = Clock::now();
  std::uint32_t n = 0;
  for (Watch* watch : watches_) {
    if (watch->stalled_ || watch->waitingSince_ == Clock::time_point{}) continue;
    if (now - watch->waitingSince_ <= watch->limit_) continue;
    watch->stalled_ = true;
    watch->context_.TryCancel();
    log_ << "holotraced: cancelled a stalled " << watch->what_ << " (no progress for " << watch->limit_.count()
         << " s)\n";
    ++n;
  }
  cancelled_ += n;
  return n;
}

std::uint64_t CallWatchdog::cancelledTotal() const {
  std::lock_guard lock(mutex_);
  return cancelled_;
}

}  // namespace ht::server
