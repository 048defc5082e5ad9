// frame_rpcs.cpp - RenderFrame, StreamFrames, Capture.
#include <chrono>
#include <cmath>
#include <cstdio>

#include "frame_io/frame_file_names.h"
#include "frame_io/frame_package.h"
#include "server/capture_output.h"
#include "server/frame_encoding.h"
#include "server/frame_job.h"
#include "server/frame_sender.h"
#include "server/holotrace_service.h"
#include "server/panel_feed.h"
#include "server/path_rules.h"
#include "server/request_checks.h"
#include "server/status_mapping.h"

namespace ht::server {
namespace v1 = holotrace::v1;
namespace {

std::string shortNumber(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", value);
  return text;
}

using Clock = std::chrono::steady_clock;

double msBetween(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double, std::milli>(b - a).count();
}

static_assert(static_cast<int>(gpu::FrameReuse::None) == v1::FRAME_REUSE_NONE &&
              static_cast<int>(gpu::FrameReuse::CachedPrimaryHits) == v1::FRAME_REUSE_CACHED_PRIMARY_HITS &&
              static_cast<int>(gpu::FrameReuse::PartialRetrace) == v1::FRAME_REUSE_PARTIAL_RETRACE);

v1::FrameHeader makeHeader(std::uint64_t frameId, const gpu::RenderResult& frame, const EncodedFrame& encoded,
                           v1::PixelFormat format, double queueMs) {
  v1::FrameHeader header;
  header.set_frame_id(frameId);
  header.set_width(encoded.width);
  header.set_height(encoded.height);
  header.set_format(format == v1::PIXEL_FORMAT_UNSPECIFIED ? v1::PIXEL_FORMAT_RGBA8 : format);
  header.set_views(encoded.views);
  header.set_render_ms(frame.totalMs);
  header.set_queue_ms(queueMs);
  header.set_reuse(static_cast<v1::FrameReuse>(frame.reuse));  // same order as gpu::FrameReuse
  header.set_traced_targets(frame.tracedTargets);
  for (const auto& stage : frame.stages) {
    auto* s = header.add_stages();
    s->set_name(stage.name);
    s->set_ms(stage.ms);
  }
  return header;
}

// Encodes `frame` for `format` into `encoded` (a stream's buffer, reused from frame to frame).
void encodeRendered(const FrameJob& job, const gpu::RenderResult& frame, v1::PixelFormat format,
                    EncodedFrame& encoded) {
  const DisplayConfig display = displayForSession(job.display->config, *job.session);
  encodeFrame(frame, checkPixelFormat(format), {display, jobCamera(job).quilt}, encoded);
}

// Encodes `frame` for the stream (encodeRendered) and hands it to `panel` (StreamRequest.present_on; none: nothing)
// through its one-slot mailbox, which never waits on the display. An RGBA8 stream's bytes serve the panel where they
// are its image (one encoding for both); for the other formats the panel gets its frame first.
void encodeAndPresent(present::PanelSink* panel, const gpu::RenderResult& frame, const FrameJob& job,
                      v1::PixelFormat format, EncodedFrame& encoded) {
  const bool rgba8 = checkPixelFormat(format) == FrameEncoding::Rgba8Srgb;
  if (panel && !rgba8) panel->submit(panelFrameOf(frame, job));
  encodeRendered(job, frame, format, encoded);
  if (panel && rgba8) panel->submit(panelFrameOf(frame, job, &encoded.bytes));
}

// Sends `frame`, encoded in `encoded`; false when the client went away or stopped reading for longer than
// limits.stream_stall_seconds (`watch` cancels the blocked Write). `streamState` set: a progressive frame's fields.
bool sendRendered(ServiceState& state, const gpu::RenderResult& frame, const EncodedFrame& encoded,
                  v1::PixelFormat format, double queueMs, std::uint64_t dropped,
                  grpc::ServerWriterInterface<v1::FramePart>& writer, CallWatchdog::Watch& watch,
                  v1::StreamState streamState = v1::STREAM_STATE_UNSPECIFIED) {
  v1::FrameHeader header = makeHeader(state.nextFrameId++, frame, encoded, format, queueMs);
  header.set_dropped_frames(dropped);
  if (streamState != v1::STREAM_STATE_UNSPECIFIED) {
    const gpu::AccumulationReport& a = frame.accumulation;
    header.set_accumulated_spp(a.minSamples);
    header.set_accumulated_spp_max(a.maxSamples);
    header.set_error_estimate(a.maxError);
    header.set_unconverged_targets(a.unconverged);
    header.set_reset_targets(a.resetTargets);
    header.set_state(streamState);
  }
  const CallWatchdog::Watch::Wait waiting(watch);
  return sendFrame(writer, std::move(header), encoded.bytes);
}

// What a stream keeps from one frame to the next: the last frame's pixels, for the next to be rendered into
// (renderFrameJob), and the buffer its frames are encoded into.
struct StreamBuffers {
  std::vector<float> pixels;
  EncodedFrame encoded;
};

// Renders one frame, encodes it and sends it (sendRendered); `panel` (StreamRequest.present_on) also gets it
// (encodeAndPresent). `buffers`' pixels are taken and, once the frame is sent, given this frame's pixels for the next.
bool renderAndSend(ServiceState& state, const std::string& client, const FrameJob& job, v1::PixelFormat format,
                   std::uint64_t dropped, grpc::ServerWriterInterface<v1::FramePart>& writer,
                   CallWatchdog::Watch& watch, StreamBuffers& buffers, present::PanelSink* panel = nullptr) {
  const auto queued = Clock::now();
  gpu::RenderResult frame = renderFrameJob(state.worker, client, job, &buffers.pixels);
  const double queueMs = std::max(0.0, msBetween(queued, Clock::now()) - frame.totalMs);
  encodeAndPresent(panel, frame, job, format, buffers.encoded);
  const bool sent = sendRendered(state, frame, buffers.encoded, format, queueMs, dropped, writer, watch);
  buffers.pixels = std::move(frame.rgba);
  return sent;
}

// Sleeps until `due` in slices of `slice`, so a cancelled call or a shutdown frees its slot within one slice.
void waitForTick(ServiceState& state, grpc::ServerContext& context, Clock::time_point due,
                 Clock::duration slice = std::chrono::milliseconds(20)) {
  while (Clock::now() < due && !context.IsCancelled()) {
    if (!state.sleepUntil(std::min(due, Clock::now() + slice))) return;
  }
}

// A converged progressive stream looks for a new scene or camera version this often (and for a cancel), whatever
// its frame rate: its only work while idle (docs/SERVICE.md §4.1).
constexpr auto kConvergedPoll = std::chrono::milliseconds(100);

frame_io::FrameFormat captureFormat(v1::CaptureFormat format) {
  switch (format) {
    case v1::CAPTURE_FORMAT_UNSPECIFIED:
    case v1::CAPTURE_FORMAT_PNG: return frame_io::FrameFormat::Png;
    case v1::CAPTURE_FORMAT_EXR: return frame_io::FrameFormat::Exr;
    default: throw BadRequest("format", "unknown capture format " + std::to_string(format));
  }
}

frame_io::ViewLayout captureLayout(v1::CaptureLayout layout) {
  switch (layout) {
    case v1::CAPTURE_LAYOUT_AUTO: return frame_io::ViewLayout::Auto;
    case v1::CAPTURE_LAYOUT_QUILT: return frame_io::ViewLayout::Quilt;
    case v1::CAPTURE_LAYOUT_VIEWS: return frame_io::ViewLayout::Views;
    default: throw BadRequest("layout", "unknown capture layout " + std::to_string(layout));
  }
}

// The files of one captured frame (proto CaptureLayout), packaged as `holotrace render` packages them.
std::vector<frame_io::FrameFile> captureFiles(const gpu::RenderResult& frame, const FrameJob& job,
                                              const std::string& stem, frame_io::FrameFormat format,
                                              frame_io::ViewLayout layout) {
  const DisplayConfig display = displayForSession(job.display->config, *job.session);
  const std::string name = stem + (format == frame_io::FrameFormat::Exr ? ".exr" : ".png");
  return frame_io::packageFrame({frame.width, frame.height, frame.views, frame.rgba}, {display, jobCamera(job).quilt},
                                layout, format, name)
      .files;
}

// The tick clock of a stream: frame k due at start + k/fps. `next()` after a frame moves to the next tick not yet
// passed and says how many ticks were missed (latest-frame-wins, docs/SERVICE.md §4 "Backpressure").
class TickClock {
 public:
  explicit TickClock(double fps)
      // <= 1000 s after the range check, >= 1 ms (limits.max_frames_per_second <= 1000): no overflow, never zero.
      : period_(std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(1.0 / fps))),
        start_(Clock::now()) {}
  std::uint64_t next() {
    const auto due = static_cast<std::uint64_t>((Clock::now() - start_) / period_) + 1;  // next tick not yet passed
    const std::uint64_t dropped = due > tick_ + 1 ? due - tick_ - 1 : 0;
    tick_ = std::max(tick_ + 1, due);
    return dropped;
  }
  std::uint64_t tick() const { return tick_; }
  Clock::time_point due() const { return start_ + period_ * static_cast<Clock::rep>(tick_); }

 private:
  Clock::duration period_;
  Clock::time_point start_;
  std::uint64_t tick_ = 0;
};

// The stop rule of a progressive stream: the request's values, else the display config's, else the daemon's.
gpu::AccumulationPolicy streamPolicy(const Limits& limits, const DisplayConfig& display,
                                     const v1::StreamRequest& request) {
  gpu::AccumulationPolicy policy;
  const float error = request.target_error();
  if (!(error >= 0.0f) || !std::isfinite(error)) {
    throw BadRequest("target_error", shortNumber(error) + " is not a finite number >= 0 (0 = the daemon default " +
                                         shortNumber(limits.streamTargetError) + ")");
  }
  policy.targetError =
      static_cast<float>(error > 0.0f ? error : display.progressiveTargetError.value_or(limits.streamTargetError));
  if (request.max_spp() > (1u << 20)) {
    throw BadRequest("max_spp", std::to_string(request.max_spp()) + " is more than 1048576 (0 = the daemon default " +
                                    std::to_string(limits.streamMaxSpp) + ")");
  }
  policy.maxSpp = request.max_spp() > 0 ? request.max_spp() : display.progressiveMaxSpp.value_or(limits.streamMaxSpp);
  policy.minSpp = std::min(policy.minSpp, policy.maxSpp);
  return policy;
}

bool progressiveMode(const v1::StreamRequest& request, const FrameJob& job) {
  switch (request.mode()) {
    // Under mpirun the default stays independent frames, which every rank renders (docs/CLUSTER.md §8); an explicit
    // PROGRESSIVE accumulates on rank 0's device alone.
    case v1::STREAM_MODE_UNSPECIFIED: return !job.session->content->quilt && !job.cluster;
    case v1::STREAM_MODE_PROGRESSIVE: return !job.session->content->quilt;  // a quilt image has no samples to add
    case v1::STREAM_MODE_INDEPENDENT: return false;
    default: throw BadRequest("mode", "unknown stream mode " + std::to_string(request.mode()));
  }
}

// Calls that share one accumulation: same session, display, camera path, per-frame spp, seed and stop rule.
std::string progressiveKey(const v1::StreamRequest& request, const FrameJob& job,
                           const gpu::AccumulationPolicy& policy) {
  const v1::RenderRequest& r = request.render();
  return r.scene_id() + '\n' + job.display->id + '\n' + (r.quilt() ? "quilt" : "native") + '\n' +
         std::to_string(job.spp) + '\n' + std::to_string(r.seed()) + '\n' + shortNumber(policy.targetError) + '\n' +
         std::to_string(policy.maxSpp);
}

// Independent frames: every tick a new frame from scratch with seed + tick.
void streamIndependent(ServiceState& state, grpc::ServerContext& context, const v1::StreamRequest& request,
                       FrameJob& job, const std::string& client, grpc::ServerWriter<v1::FramePart>& writer,
                       CallWatchdog::Watch& watch, present::PanelSink* panel) {
  TickClock clock(request.frames_per_second());
  std::uint64_t dropped = 0;
  StreamBuffers buffers;
  while (!context.IsCancelled()) {
    if (state.shuttingDown) throw ShuttingDown("holotraced is shutting down");
    job.session = state.scenes.find(request.render().scene_id());  // picks up UpdateScene
    job.seed = request.render().seed() + static_cast<std::uint32_t>(clock.tick());
    if (!renderAndSend(state, client, job, request.render().format(), dropped, writer, watch, buffers, panel)) {
      return;
    }
    dropped = clock.next();
    waitForTick(state, context, clock.due());
  }
}

// Progressive frames (docs/REUSE.md §1-§2): each tick adds samples to the stream's shared accumulation, unless it
// has converged for the current session (scene and camera version), in which case nothing is rendered and the last
// frame is sent only to a caller that has not had it. The accumulation restarts by itself when the renderer's scene
// or the camera changed (gpu/accumulator.h), so an edit never mixes samples of two scene versions.
void streamProgressive(ServiceState& state, grpc::ServerContext& context, const v1::StreamRequest& request,
                       FrameJob& job, const std::string& client, grpc::ServerWriter<v1::FramePart>& writer,
                       CallWatchdog::Watch& watch, present::PanelSink* panel) {
  const gpu::AccumulationPolicy policy = streamPolicy(state.config.limits, job.display->config, request);
  const std::uint64_t bytes = gpu::Accumulator::bytesFor(displayFrameShape(*job.display, job.path));
  ProgressiveStreams::Membership member(
      state.progressive, state.progressive.join(progressiveKey(request, job, policy), request.render().scene_id(),
                                                job.display->id, bytes, policy));
  ProgressiveStream& stream = member.stream();
  TickClock clock(request.frames_per_second());
  std::uint64_t dropped = 0, sentFrame = 0;
  EncodedFrame encoded;  // reused by every frame this call sends
  while (!context.IsCancelled()) {
    if (state.shuttingDown) throw ShuttingDown("holotraced is shutting down");
    job.session = state.scenes.find(request.render().scene_id());  // picks up UpdateScene
    std::shared_ptr<const gpu::RenderResult> frame;
    std::uint64_t frameNumber = 0;
    double queueMs = 0.0;
    {
      std::lock_guard lock(stream.frameMutex);
      const bool idle = stream.last && stream.session == job.session && stream.last->accumulation.converged;
      if (!idle) {
        const auto queued = Clock::now();
        auto rendered = std::make_shared<const gpu::RenderResult>(
            accumulateFrameJob(state.worker, client, job, *stream.accumulator));
        queueMs = std::max(0.0, msBetween(queued, Clock::now()) - rendered->totalMs);
        stream.recordFrame(std::move(rendered), job.session);
      }
      frame = stream.last;
      frameNumber = stream.frameNumber;
    }
    const bool converged = frame->accumulation.converged;
    if (frameNumber != sentFrame) {
      // the panel gets each new sum / n, the converged one last
      encodeAndPresent(panel, *frame, job, request.render().format(), encoded);
      const v1::StreamState shown = converged ? v1::STREAM_STATE_CONVERGED : v1::STREAM_STATE_ACCUMULATING;
      if (!sendRendered(state, *frame, encoded, request.render().format(), queueMs, dropped, writer, watch, shown)) {
        return;
      }
      sentFrame = frameNumber;
    }
    dropped = clock.next();
    if (converged) {
      waitForTick(state, context, std::max(clock.due(), Clock::now() + kConvergedPoll), kConvergedPoll);
    } else {
      waitForTick(state, context, clock.due());
    }
  }
}

}  // namespace

grpc::Status HolotraceService::RenderFrame(grpc::ServerContext* context, const v1::RenderRequest* request,
                                           grpc::ServerWriter<v1::FramePart>* writer) {
  return guarded([&] {
    FrameJob job = checkRenderRequest(state_, *request);
    StreamSlot slot(state_);
    if (job.reuse) {  // the session's own Renderer keeps the state, so that its first edit reuses it too
      job.session = state_.scenes.ownRenderer(clientKey(*context), request->scene_id());
    }
    CallWatchdog::Watch watch(state_.watchdog, *context, state_.config.limits.streamStallSeconds, "RenderFrame");
    StreamBuffers buffers;
    if (!renderAndSend(state_, clientKey(*context), job, request->format(), 0, *writer, watch, buffers)) {
      throw ClientGone("client closed the stream");
    }
    return grpc::Status::OK;
  });
}

// Frames on a fixed clock (frame k due at start + k/fps). A frame is rendered only when the previous one has been
// written, so a slow client is never queued old frames: it gets the newest, and dropped_frames counts the ticks
// it missed (latest-frame-wins, docs/SERVICE.md §4 "Backpressure"). Progressive by default (docs/SERVICE.md §2
// "StreamFrames modes").
grpc::Status HolotraceService::StreamFrames(grpc::ServerContext* context, const v1::StreamRequest* request,
                                            grpc::ServerWriter<v1::FramePart>* writer) {
  return guarded([&] {
    // The range first: 1/fps of a tiny rate overflows the clock's 64-bit nanoseconds (and a NaN compares false).
    const double fps = request->frames_per_second();
    if (!(fps >= kMinFramesPerSecond && fps <= state_.config.limits.maxFramesPerSecond)) {
      throw BadRequest("frames_per_second", shortNumber(fps) + " is not in [" + shortNumber(kMinFramesPerSecond) +
                                                ", " + shortNumber(state_.config.limits.maxFramesPerSecond) +
                                                "] (limits.max_frames_per_second)");
    }
    FrameJob job = checkRenderRequest(state_, request->render());
    std::shared_ptr<present::PanelSink> panel;
    if (!request->present_on().empty()) panel = streamPanelSink(state_, request->present_on(), job);
    const bool progressive = progressiveMode(*request, job);
    StreamSlot slot(state_);
    const SceneLibrary::Pin pin(state_.scenes, request->render().scene_id());  // not idled out between slow frames
    CallWatchdog::Watch watch(state_.watchdog, *context, state_.config.limits.streamStallSeconds, "StreamFrames");
    const std::string client = clientKey(*context);
    if (progressive && job.reuse) {  // from the first frame on the renderer the session's node moves will update
      job.session = state_.scenes.ownRenderer(client, request->render().scene_id(), true);
    }
    if (progressive) {
      streamProgressive(state_, *context, *request, job, client, *writer, watch, panel.get());
    } else {
      streamIndependent(state_, *context, *request, job, client, *writer, watch, panel.get());
    }
    return grpc::Status(grpc::StatusCode::CANCELLED, "client cancelled the stream");
  });
}

grpc::Status HolotraceService::Capture(grpc::ServerContext* context, const v1::CaptureRequest* request,
                                       grpc::ServerWriter<v1::CaptureProgress>* writer) {
  return guarded([&] {
    checkFileNameComponent("name", request->name());
    const std::uint32_t frames = request->frames() == 0 ? 1 : request->frames();
    if (frames > state_.config.limits.maxCaptureFrames) {
      throw LimitExceeded("frames = " + std::to_string(frames) + " (limits.max_capture_frames = " +
                          std::to_string(state_.config.limits.maxCaptureFrames) + ")");
    }
    const frame_io::FrameFormat format = captureFormat(request->format());
    const frame_io::ViewLayout layout = captureLayout(request->layout());
    FrameJob job = checkRenderRequest(state_, request->render());
    const gpu::DisplayCamera camera = jobCamera(job);
    if (!frame_io::layoutAllowed({job.display->config, camera.quilt}, camera.shape.views, layout)) {
      throw BadRequest("layout",
                       "the views of display '" + job.display->id + "' do not form a quilt; use CAPTURE_LAYOUT_VIEWS");
    }
    StreamSlot slot(state_);
    const SceneLibrary::Pin pin(state_.scenes, request->render().scene_id());
    CallWatchdog::Watch watch(state_.watchdog, *context, state_.config.limits.streamStallSeconds, "Capture");
    CaptureOutput output(state_.outputSink, request->name(), request->overwrite());  // the name is ours till the end
    const std::string client = clientKey(*context);
    const auto checkGoing = [&](std::uint32_t done) {  // before a render, and before writing what was rendered
      if (context->IsCancelled())
        throw ClientGone("capture cancelled after " + std::to_string(done) + " complete frames");
      if (state_.shuttingDown) throw ShuttingDown("shutting down after " + std::to_string(done) + " complete frames");
    };
    for (std::uint32_t i = 0; i < frames; ++i) {
      checkGoing(i);
      job.seed = request->render().seed() + i;
      const gpu::RenderResult frame = renderFrameJob(state_.worker, client, job);
      const std::vector<frame_io::FrameFile> files =
          captureFiles(frame, job, frame_io::captureFrameStem(request->name(), i), format, layout);
      checkGoing(i);             // no file after a cancel
      output.writeFrame(files);  // the frame's files whole or not at all
      for (const frame_io::FrameFile& file : files) {
        v1::CaptureProgress progress;
        progress.set_frames_done(i + 1);
        progress.set_frames_total(frames);
        progress.set_file(file.name);
        const CallWatchdog::Watch::Wait waiting(watch);
        writer->Write(progress);  // a gone or stalled client is noticed at the next frame (IsCancelled)
      }
    }
    return grpc::Status::OK;
  });
}

}  // namespace ht::server
