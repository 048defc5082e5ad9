// holotrace_service.h - the holotrace.v1.Holotrace RPC handlers (synchronous gRPC API: each streaming call runs on
// its own gRPC thread and blocks in Write(), which HTTP/2 flow control holds back for a slow client, docs/SERVICE.md
// §4 "Backpressure"; frames are only rendered when the stream can take them, so a slow client gets the newest frame).
#pragma once
#include "holotrace/v1/holotrace.grpc.pb.h"
#include "server/service_state.h"

namespace ht::server {

class HolotraceService final : public holotrace::v1::Holotrace::Service {
 public:
  explicit HolotraceService(ServiceState& state) : state_(state) {}

  grpc::Status ListDisplays(grpc::ServerContext*, const holotrace::v1::ListDisplaysRequest*,
                            holotrace::v1::ListDisplaysResponse*) override;
  grpc::Status GetDisplay(grpc::ServerContext*, const holotrace::v1::GetDisplayRequest*,
                          holotrace::v1::Display*) override;
  grpc::Status LoadScene(grpc::ServerContext*, const holotrace::v1::LoadSceneRequest*,
                         holotrace::v1::SceneHandle*) override;
  grpc::Status UploadScene(grpc::ServerContext*, grpc::ServerReader<holotrace::v1::UploadSceneChunk>*,
                           holotrace::v1::SceneHandle*) override;
  grpc::Status UpdateScene(grpc::ServerContext*, const holotrace::v1::UpdateSceneRequest*,
                           holotrace::v1::UpdateSceneResponse*) override;
  grpc::Status RenderFrame(grpc::ServerContext*, const holotrace::v1::RenderRequest*,
                           grpc::ServerWriter<holotrace::v1::FramePart>*) override;
  grpc::Status StreamFrames(grpc::ServerContext*, const holotrace::v1::StreamRequest*,
                            grpc::ServerWriter<holotrace::v1::FramePart>*) override;
  grpc::Status Capture(grpc::ServerContext*, const holotrace::v1::CaptureRequest*,
                       grpc::ServerWriter<holotrace::v1::CaptureProgress>*) override;
  grpc::Status Status(grpc::ServerContext*, const holotrace::v1::StatusRequest*,
                      holotrace::v1::StatusResponse*) override;

 private:
  ServiceState& state_;
};

// Fair-queueing key of a call: gRPC reports every unix-socket peer as "unix:", so each call is its own client.
std::string clientKey(const grpc::ServerContext& context);

}  // namespace ht::server
