// frame_sender.cpp - see frame_sender.h.
#include "server/frame_sender.h"

#include <algorithm>

namespace ht::server {

bool sendFrame(grpc::ServerWriterInterface<holotrace::v1::FramePart>& writer, holotrace::v1::FrameHeader header,
               const std::vector<std::uint8_t>& bytes) {
  const std::uint64_t frameId = header.frame_id();
  header.set_total_bytes(bytes.size());
  holotrace::v1::FramePart part;
  *part.mutable_header() = std::move(header);
  if (!writer.Write(part)) return false;
  for (std::size_t offset = 0; offset < bytes.size(); offset += kChunkBytes) {
    const std::size_t n = std::min(kChunkBytes, bytes.size() - offset);
    holotrace::v1::FramePart chunk;
    chunk.mutable_chunk()->set_frame_id(frameId);
    chunk.mutable_chunk()->set_offset(offset);
    chunk.mutable_chunk()->set_data(bytes.data() + offset, n);
    if (!writer.Write(chunk)) return false;
  }
  return true;
}

}  // namespace ht::server
