// daemon.cpp - see daemon.h.
#include "server/daemon.h"

#include <grpcpp/ext/proto_server_reflection_plugin.h>
#include <grpcpp/grpcpp.h>
#include <grpcpp/health_check_service_interface.h>
#include <malloc.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <thread>

#include "common/error.h"
#include "gpu/vulkan_context.h"
#include "server/holotrace_service.h"
#include "server/listen_address.h"
#include "server/panel_sinks.h"

namespace ht::server {

namespace {

SceneLibraryLimits sceneLimits(const Limits& limits) {
  return {limits.maxTriangles, limits.maxSceneSessions, limits.sceneIdleSeconds, limits.maxSceneMemoryBytes};
}

}  // namespace

struct Daemon::Parts {
  DaemonConfig config;
  std::ostream& log;
  std::vector<ListenClaim> claims;  // before the device: a second daemon is refused before it opens anything
  bool ownsWorkDir = false;
  gpu::VulkanContext context;
  RenderWorker worker;
  std::unique_ptr<SceneLibrary> scenes;
  DisplayRegistry displays;
  FileSink outputSink;
  UploadBudget uploads;
  CallWatchdog watchdog;
  ProgressiveStreams progressive;  // accumulations released on the worker, before it stops
  ServiceState state;
  HolotraceService service;
  std::unique_ptr<PanelSinks> panels;  // display sinks ("present"); their threads end before the state they read
  std::unique_ptr<DistributedFrames> cluster;
  std::unique_ptr<grpc::Server> server;
  std::thread janitor;  // ends idle scene sessions (SceneLibrary::sweep), cancels stalled calls (CallWatchdog)
  bool stopped = false;

  Parts(DaemonConfig c, std::ostream& l, std::vector<ListenClaim> owned, bool ownsWork)
      : config(std::move(c)),
        log(l),
        claims(std::move(owned)),
        ownsWorkDir(ownsWork),
        context({config.deviceIndex, false}),
        worker(context, config.limits.maxFramesInFlight),
        scenes(std::make_unique<SceneLibrary>(worker, sceneLimits(config.limits))),
        displays(config.displaysDir, deviceScanFor(config.devices)),
        outputSink(config.outputRoot),
        uploads(config.limits.maxUploads, config.limits.maxUploadBytesInFlight),
        watchdog(l),
        progressive(worker, config.limits.maxAccumulatorBytes),
        state{config, displays, *scenes, worker, outputSink, uploads, watchdog, progressive},
        service(state) {}
};

namespace {

// Until shutdown, every min(1 s, shortest idle/stall limit / 4): cancels stalled calls, ends idle sessions, evicts.
void runJanitor(ServiceState& state, CallWatchdog& watchdog, SceneLibrary& scenes) {
  const Limits& l = state.config.limits;
  const double shortest = std::min({l.sceneIdleSeconds, l.uploadIdleSeconds, l.streamStallSeconds});
  const auto period = std::chrono::duration_cast<std::chrono::steady_clock::duration>(
      std::chrono::duration<double>(std::clamp(shortest / 4.0, 0.02, 1.0)));
  while (state.sleepUntil(std::chrono::steady_clock::now() + period)) {
    const bool cancelled = watchdog.check() != 0;
    // glibc keeps freed blocks in the arena of the thread that freed them (every gRPC thread gets one), so released
    // scenes and uploads stay resident (+70 MiB at rest after a one-minute soak, bench/soak_main.cpp);
    // malloc_trim(0) hands the free pages of all arenas back to the OS (malloc_trim(3)).
    if (scenes.sweep() || cancelled) ::malloc_trim(0);
  }
}

DaemonConfig withWorkDir(DaemonConfig config, bool& owns) {
  owns = config.workDir.empty();
  if (owns) { config.workDir = std::filesystem::temp_directory_path() / ("holotraced-" + std::to_string(::getpid())); }
  std::filesystem::create_directories(config.workDir);
  ::chmod(config.workDir.c_str(), 0700);
  return config;
}

}  // namespace

Daemon::Daemon(DaemonConfig config, std::ostream& log, std::unique_ptr<DistributedFrames> cluster) {
  for (const std::string& address : config.listen) checkListenAddress(config.sourcePath, address);
  std::vector<ListenClaim> claims;
  for (const std::string& address : config.listen) claims.emplace_back(address);  // throws AddressInUse
  bool owns = false;
  config = withWorkDir(std::move(config), owns);
  parts_ = std::make_unique<Parts>(std::move(config), log, std::move(claims), owns);
  log << "holotraced: device " << parts_->context.device().name << ", " << parts_->displays.reload(log)
      << " displays\n";
  const DaemonConfig& c = parts_->config;
  parts_->panels = std::make_unique<PanelSinks>(c.present, parts_->displays, c.deviceIndex, c.sourcePath, log);
  parts_->state.panels = parts_->panels.get();
  parts_->cluster = std::move(cluster);
  parts_->state.cluster = parts_->cluster.get();
  if (parts_->panels->size() > 0) log << "holotraced: " << parts_->panels->size() << " panel sink(s)\n";
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
  for (const ListenClaim& claim : parts_->claims)
    builder.AddListeningPort(claim.address(), grpc::InsecureServerCredentials());
  builder.AddChannelArgument(GRPC_ARG_ALLOW_REUSEPORT, 0);  // gRPC's default shares a TCP port with a second daemon
  builder.SetMaxReceiveMessageSize(static_cast<int>(parts_->config.limits.maxMessageBytes));
  builder.AddChannelArgument(GRPC_ARG_KEEPALIVE_TIME_MS, 60'000);  // notice dead peers (docs/SERVICE.md §4)
  builder.AddChannelArgument(GRPC_ARG_KEEPALIVE_TIMEOUT_MS, 20'000);
  builder.RegisterService(&parts_->service);
  parts_->server = builder.BuildAndStart();
  if (!parts_->server) throw IoError("holotraced: cannot listen on the configured addresses (in use? permissions?)");
  parts_->janitor = std::thread([this] { runJanitor(parts_->state, parts_->watchdog, *parts_->scenes); });
  for (const ListenClaim& claim : parts_->claims) {
    claim.finish();
    parts_->log << "holotraced: listening on " << claim.address() << "\n";
  }
}

void Daemon::shutdown(std::chrono::milliseconds grace) {
  if (parts_->stopped) return;
  parts_->stopped = true;
  parts_->state.beginShutdown();
  if (parts_->janitor.joinable()) parts_->janitor.join();
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
  if (parts_->cluster) parts_->cluster->stop();  // after the last frame: the other ranks end cleanly
  parts_->claims.clear();                        // removes our sockets, releases the locks
}

// Displays first, then the panels: a display that appeared (a panel plugged in, a config added) gets its sink, one
// that is gone loses it; running sinks of unchanged displays are not touched.
std::size_t Daemon::reloadDisplays() {
  const std::size_t count = parts_->displays.reload(parts_->log);
  parts_->panels->update(parts_->displays);
  return count;
}

}  // namespace ht::server
