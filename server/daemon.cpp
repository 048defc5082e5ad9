// daemon.cpp - see daemon.h.
#include "server/daemon.h"

#include <grpcpp/ext/proto_server_reflection_plugin.h>
#include <grpcpp/grpcpp.h>
#include <grpcpp/health_check_service_interface.h>
#include <sys/stat.h>
#include <unistd.h>

#include <thread>

#include "common/error.h"
#include "gpu/vulkan_context.h"
#include "server/holotrace_service.h"
#include "server/listen_address.h"

namespace ht::server {

struct Daemon::Parts {
  DaemonConfig config;
  std::ostream& log;
  bool ownsWorkDir = false;
  gpu::VulkanContext context;
  RenderWorker worker;
  std::unique_ptr<SceneLibrary> scenes;
  DisplayRegistry displays;
  FileSink outputSink;
  FileSink uploadSink;
  ServiceState state;
  HolotraceService service;
  std::unique_ptr<grpc::Server> server;
  bool stopped = false;

  Parts(DaemonConfig c, std::ostream& l, bool ownsWork)
      : config(std::move(c)),
        log(l),
        ownsWorkDir(ownsWork),
        context({config.deviceIndex, false}),
        worker(context, config.limits.maxFramesInFlight),
        scenes(std::make_unique<SceneLibrary>(worker, config.limits.maxTriangles)),
        displays(config.displaysDir),
        outputSink(config.outputRoot),
        uploadSink(config.workDir),
        state{config, displays, *scenes, worker, outputSink, uploadSink},
        service(state) {}
};

namespace {

DaemonConfig withWorkDir(DaemonConfig config, bool& owns) {
  owns = config.workDir.empty();
  if (owns) { config.workDir = std::filesystem::temp_directory_path() / ("holotraced-" + std::to_string(::getpid())); }
  std::filesystem::create_directories(config.workDir);
  ::chmod(config.workDir.c_str(), 0700);
  return config;
}

}  // namespace

Daemon::Daemon(DaemonConfig config, std::ostream& log) {
  for (const std::string& address : config.listen) checkListenAddress(config.sourcePath, address);
  bool owns = false;
  config = withWorkDir(std::move(config), owns);
  parts_ = std::make_unique<Parts>(std::move(config), log, owns);
  log << "holotraced: device " << parts_->context.device().name << ", " << parts_->displays.reload(log)
      << " displays\n";
}

Daemon::~Daemon() {
  shutdown(std::chrono::milliseconds(0));
  parts_->scenes.reset();  // Renderers go before the Vulkan context
  if (parts_->ownsWorkDir) {
    std::error_code ec;
    std::filesystem::remove_all(parts_->config.workDir, ec);
  }
}

void Daemon::start() {
  grpc::EnableDefaultHealthCheckService(true);  // grpc.health.v1 (docs/SERVICE.md §4 "Health")
  grpc::reflection::InitProtoReflectionServerBuilderPlugin();
  grpc::ServerBuilder builder;
  for (const std::string& address : parts_->config.listen) {
    prepareListenAddress(address);
    builder.AddListeningPort(address, grpc::InsecureServerCredentials());
  }
  builder.SetMaxReceiveMessageSize(static_cast<int>(parts_->config.limits.maxMessageBytes));
  builder.AddChannelArgument(GRPC_ARG_KEEPALIVE_TIME_MS, 60'000);  // notice dead peers (docs/SERVICE.md §4)
  builder.AddChannelArgument(GRPC_ARG_KEEPALIVE_TIMEOUT_MS, 20'000);
  builder.RegisterService(&parts_->service);
  parts_->server = builder.BuildAndStart();
  if (!parts_->server) throw IoError("holotraced: cannot listen on the configured addresses (in use? permissions?)");
  for (const std::string& address : parts_->config.listen) {
    finishListenAddress(address);
    parts_->log << "holotraced: listening on " << address << "\n";
  }
}

void Daemon::shutdown(std::chrono::milliseconds grace) {
  if (parts_->stopped) return;
  parts_->stopped = true;
  parts_->state.beginShutdown();
  if (parts_->server) {
    if (auto* health = parts_->server->GetHealthCheckService()) health->Shutdown();
    // Our streams stop at their next frame boundary; wait for that (up to `grace`), then give gRPC a short
    // deadline: with a longer one, Shutdown() waits it out while an idle client keeps its connection open.
    const auto drainUntil = std::chrono::steady_clock::now() + grace;
    while (parts_->state.activeStreams.load() != 0 && std::chrono::steady_clock::now() < drainUntil) {
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    parts_->server->Shutdown(std::chrono::system_clock::now() + std::chrono::milliseconds(250));
    parts_->server->Wait();
  }
  parts_->worker.stop();
  for (const std::string& address : parts_->config.listen) removeListenAddress(address);
}

std::size_t Daemon::reloadDisplays() { return parts_->displays.reload(parts_->log); }

}  // namespace ht::server
