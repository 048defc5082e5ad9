// load_stream_client.cpp - see load_stream_client.h.
#include "bench/load_stream_client.h"

#include <grpcpp/grpcpp.h>

#include <thread>

#include "holotrace/v1/holotrace.grpc.pb.h"

namespace ht::bench {
namespace v1 = holotrace::v1;

bool LoadStop::reached(const LoadTotals& totals) const {
  return std::chrono::steady_clock::now() >= end || (frames > 0 && totals.frames.load() >= frames);
}

namespace {

void countFrame(const v1::FrameHeader& header, LoadTotals& totals) {
  totals.frames.fetch_add(1);
  std::lock_guard lock(totals.mutex);
  totals.latencyMs.push_back(header.queue_ms() + header.render_ms());
  totals.dropped += header.dropped_frames();
  totals.bytes += header.total_bytes();
}

// One StreamFrames call until `maxFrames` frames (0 = unlimited), `stop`, or the call ends; false if it failed.
bool streamOnce(v1::Holotrace::Stub& stub, const v1::StreamRequest& request, const LoadStop& stop,
                std::uint64_t maxFrames, LoadTotals& totals) {
  grpc::ClientContext context;
  auto reader = stub.StreamFrames(&context, request);
  totals.calls.fetch_add(1);
  v1::FramePart part;
  v1::FrameHeader header;
  std::uint64_t got = 0, frames = 0;
  bool open = true;
  while (!stop.reached(totals) && (maxFrames == 0 || frames < maxFrames) && (open = reader->Read(&part))) {
    if (part.has_header()) {
      header = part.header();
      got = 0;
    } else {
      got += part.chunk().data().size();
    }
    if (header.total_bytes() > 0 && got == header.total_bytes()) {
      countFrame(header, totals);
      ++frames;
      got = 0;
    }
  }
  context.TryCancel();
  while (open && reader->Read(&part)) {}
  const grpc::Status status = reader->Finish();
  if (!status.ok() && status.error_code() != grpc::StatusCode::CANCELLED) {
    std::lock_guard lock(totals.mutex);
    ++totals.failedCalls;
    totals.lastError = status.error_message();
    return false;
  }
  return true;
}

}  // namespace

void runStreamClient(const std::string& address, const v1::StreamRequest& request, const LoadStop& stop,
                     std::uint64_t reconnectEvery, LoadTotals& totals) {
  grpc::ChannelArguments args;
  args.SetMaxReceiveMessageSize(64 << 20);
  args.SetInt("grpc.use_local_subchannel_pool", 1);  // one connection per simulated client
  auto stub = v1::Holotrace::NewStub(grpc::CreateCustomChannel(address, grpc::InsecureChannelCredentials(), args));
  while (!stop.reached(totals)) {
    if (!streamOnce(*stub, request, stop, reconnectEvery, totals)) {
      std::this_thread::sleep_for(std::chrono::milliseconds(100));  // e.g. max_clients busy: retry, do not spin
    }
  }
}

}  // namespace ht::bench
