// render_worker.cpp - see render_worker.h.
#include "server/render_worker.h"

#include <chrono>

#include "server/path_rules.h"

namespace ht::server {

RenderWorker::RenderWorker(gpu::VulkanContext& context, std::uint32_t maxInFlightPerClient)
    : context_(context), maxInFlight_(maxInFlightPerClient) {
  stats_.deviceName = context.device().name;
  thread_ = std::thread([this] { run(); });
}

RenderWorker::~RenderWorker() { stop(); }

std::future<void> RenderWorker::submit(const std::string& client, Job job, bool countsAsFrame) {
  std::lock_guard lock(mutex_);
  if (stopping_) throw ShuttingDown("holotraced is shutting down");
  std::uint32_t& inFlight = inFlight_[client];
  if (inFlight >= maxInFlight_) {
    throw LimitExceeded("client has " + std::to_string(inFlight) +
                        " frames in flight (limits.max_frames_in_flight = " + std::to_string(maxInFlight_) + ")");
  }
  ++inFlight;
  std::deque<Task>& queue = queues_[client];
  if (queue.empty()) roundRobin_.push_back(client);
  queue.push_back(Task{std::move(job), {}, countsAsFrame});
  auto future = queue.back().done.get_future();
  wake_.notify_one();
  return future;
}

bool RenderWorker::takeNext(Task& task, std::string& client) {
  std::unique_lock lock(mutex_);
  wake_.wait(lock, [this] { return stopping_ || !roundRobin_.empty(); });
  if (roundRobin_.empty()) return false;  // stopping and drained
  client = roundRobin_.front();
  roundRobin_.pop_front();
  std::deque<Task>& queue = queues_[client];
  task = std::move(queue.front());
  queue.pop_front();
  if (!queue.empty())
    roundRobin_.push_back(client);  // its next job waits behind the other clients
  else
    queues_.erase(client);
  return true;
}

void RenderWorker::finish(const std::string& client, double ms, bool countsAsFrame) {
  std::lock_guard lock(mutex_);
  if (--inFlight_[client] == 0) inFlight_.erase(client);
  if (!countsAsFrame) return;
  ++stats_.framesRendered;
  stats_.lastFrameMs = ms;
  totalFrameMs_ += ms;
}

void RenderWorker::run() {
  Task task;
  std::string client;
  while (takeNext(task, client)) {
    const auto start = std::chrono::steady_clock::now();
    try {
      task.job(context_);
      task.done.set_value();
    } catch (...) { task.done.set_exception(std::current_exception()); }
    finish(client, std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count(),
           task.countsAsFrame);
  }
}

void RenderWorker::stop() {
  {
    std::lock_guard lock(mutex_);
    if (stopping_ && !thread_.joinable()) return;
    stopping_ = true;
    for (auto& [client, queue] : queues_) {
      for (Task& task : queue) {
        task.done.set_exception(std::make_exception_ptr(ShuttingDown("holotraced is shutting down")));
      }
      std::uint32_t& n = inFlight_[client];
      n -= static_cast<std::uint32_t>(queue.size());
      if (n == 0) inFlight_.erase(client);
    }
    queues_.clear();
    roundRobin_.clear();
  }
  wake_.notify_all();
  if (thread_.joinable()) thread_.join();
}

WorkerStats RenderWorker::stats() const {
  std::lock_guard lock(mutex_);
  WorkerStats s = stats_;
  s.meanFrameMs = s.framesRendered ? totalFrameMs_ / static_cast<double>(s.framesRendered) : 0.0;
  for (const auto& [client, n] : inFlight_) s.queued += n;
  return s;
}

}  // namespace ht::server
