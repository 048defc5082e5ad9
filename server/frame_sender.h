// frame_sender.h - one frame on a server stream: a FrameHeader message, then FrameChunk messages of at most
// kChunkBytes (docs/SERVICE.md §4: 1-4 MiB chunks instead of one large message).
#pragma once
#include <grpcpp/support/sync_stream.h>

#include <cstdint>
#include <vector>

#include "holotrace/v1/holotrace.pb.h"

namespace ht::server {

inline constexpr std::size_t kChunkBytes = 1u << 20;

// Returns false when the stream is closed (client gone / cancelled); the rest is then not sent.
bool sendFrame(grpc::ServerWriterInterface<holotrace::v1::FramePart>& writer, holotrace::v1::FrameHeader header,
               const std::vector<std::uint8_t>& bytes);

}  // namespace ht::server
