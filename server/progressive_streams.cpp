// progressive_streams.cpp - see progressive_streams.h.
#include "server/progressive_streams.h"

#include <algorithm>

#include "server/errors.h"

namespace ht::server {

void ProgressiveStream::recordFrame(std::shared_ptr<const gpu::RenderResult> frame,
                                    std::shared_ptr<const SceneSession> shown) {
  session = std::move(shown);
  last = std::move(frame);
  ++frameNumber;
  std::lock_guard lock(statusMutex);
  report = last->accumulation;
  ++framesRendered;
}

ProgressiveStreams::~ProgressiveStreams() {
  std::lock_guard lock(mutex_);
  for (auto& [key, stream] : streams_) {
    std::lock_guard frame(stream->frameMutex);
    stream->accumulator.reset();  // callers are gone: the daemon stops the worker before the registries
  }
}

std::shared_ptr<ProgressiveStream> ProgressiveStreams::join(const std::string& key, const std::string& sceneId,
                                                            const std::string& displayId, std::uint64_t bytes,
                                                            const gpu::AccumulationPolicy& policy) {
  std::lock_guard lock(mutex_);
  auto found = streams_.find(key);
  if (found != streams_.end()) {
    ++found->second->clients;
    return found->second;
  }
  if (bytes > limitBytes_ - std::min(limitBytes_, bytesInUse_)) {
    throw LimitExceeded("progressive stream of scene '" + sceneId + "' on display '" + displayId + "' needs " +
                        std::to_string(bytes) + " bytes of accumulator memory, " + std::to_string(bytesInUse_) +
                        " in use by other streams (limits.max_accumulator_bytes = " + std::to_string(limitBytes_) +
                        "); raise the limit, end other streams, or use STREAM_MODE_INDEPENDENT");
  }
  auto stream = std::make_shared<ProgressiveStream>();
  stream->key = key;
  stream->sceneId = sceneId;
  stream->displayId = displayId;
  stream->bytes = bytes;
  stream->accumulator = std::make_shared<gpu::Accumulator>(policy);
  stream->clients = 1;
  bytesInUse_ += bytes;
  streams_.emplace(key, stream);
  return stream;
}

void ProgressiveStreams::leave(const std::shared_ptr<ProgressiveStream>& stream) {
  std::shared_ptr<gpu::Accumulator> released;
  {
    std::lock_guard lock(mutex_);
    if (--stream->clients > 0) return;
    streams_.erase(stream->key);
    bytesInUse_ -= stream->bytes;
    std::lock_guard frame(stream->frameMutex);
    released = std::move(stream->accumulator);
  }
  worker_.dispose([released] {});  // the device buffers go on the worker thread
}

std::vector<StreamStatusEntry> ProgressiveStreams::status() const {
  std::vector<std::shared_ptr<ProgressiveStream>> streams;
  std::vector<StreamStatusEntry> entries;
  {
    std::lock_guard lock(mutex_);
    for (const auto& [key, stream] : streams_) {
      streams.push_back(stream);
      entries.push_back({stream->sceneId, stream->displayId, {}, stream->clients, 0, stream->bytes});
    }
  }
  for (std::size_t i = 0; i < streams.size(); ++i) {
    std::lock_guard shown(streams[i]->statusMutex);
    entries[i].report = streams[i]->report;
    entries[i].framesRendered = streams[i]->framesRendered;
  }
  return entries;
}

std::uint64_t ProgressiveStreams::bytesInUse() const {
  std::lock_guard lock(mutex_);
  return bytesInUse_;
}

}  // namespace ht::server
