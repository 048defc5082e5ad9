// frame_rpcs.cpp - RenderFrame, StreamFrames, Capture.
#include <chrono>
#include <cmath>
#include <cstdio>

#include "camera_models/quilt_layout.h"
#include "cli/image_file_writer.h"
#include "gpu/view_mosaic.h"
#include "server/frame_encoding.h"
#include "server/frame_job.h"
#include "server/frame_sender.h"
#include "server/holotrace_service.h"
#include "server/path_rules.h"
#include "server/request_checks.h"
#include "server/status_mapping.h"

namespace ht::server {
namespace v1 = holotrace::v1;
namespace {

using Clock = std::chrono::steady_clock;

double msBetween(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double, std::milli>(b - a).count();
}

v1::FrameHeader makeHeader(std::uint64_t frameId, const gpu::RenderResult& frame, v1::PixelFormat format,
                           double queueMs) {
  v1::FrameHeader header;
  header.set_frame_id(frameId);
  header.set_width(frame.width);
  header.set_height(frame.height);
  header.set_format(format == v1::PIXEL_FORMAT_UNSPECIFIED ? v1::PIXEL_FORMAT_RGBA8 : format);
  header.set_views(frame.views);
  header.set_render_ms(frame.totalMs);
  header.set_queue_ms(queueMs);
  for (const auto& stage : frame.stages) {
    auto* s = header.add_stages();
    s->set_name(stage.name);
    s->set_ms(stage.ms);
  }
  return header;
}

// Renders one frame and sends it; false when the client went away.
bool renderAndSend(ServiceState& state, const std::string& client, const FrameJob& job, v1::PixelFormat format,
                   std::uint64_t dropped, grpc::ServerWriterInterface<v1::FramePart>& writer) {
  const auto queued = Clock::now();
  gpu::RenderResult frame = renderFrameJob(state.worker, client, job);
  const double queueMs = std::max(0.0, msBetween(queued, Clock::now()) - frame.totalMs);
  if (frame.views > 1 && format == v1::PIXEL_FORMAT_PNG) frame = gpu::singleImage(frame, jobCamera(job).quilt);
  const auto bytes = encodeFrame(frame, checkPixelFormat(format));
  v1::FrameHeader header = makeHeader(state.nextFrameId++, frame, format, queueMs);
  header.set_dropped_frames(dropped);
  return sendFrame(writer, std::move(header), bytes);
}

// Sleeps until `due` in short slices, so a cancelled call or a shutdown frees its slot within ~20 ms.
void waitForTick(ServiceState& state, grpc::ServerContext& context, Clock::time_point due) {
  while (Clock::now() < due && !context.IsCancelled()) {
    if (!state.sleepUntil(std::min(due, Clock::now() + std::chrono::milliseconds(20)))) return;
  }
}

std::string captureStem(const std::string& name, std::uint32_t index) {
  char suffix[32];
  std::snprintf(suffix, sizeof suffix, "_f%04u", index);
  return name + suffix;
}

std::string viewSuffix(std::uint32_t view, std::uint32_t views) {
  const std::size_t digits = std::max<std::size_t>(2, std::to_string(views - 1).size());
  const std::string number = std::to_string(view);
  return "_v" + std::string(digits - number.size(), '0') + number;
}

struct CaptureFile {
  std::string name;
  std::vector<std::uint8_t> bytes;
};

// The files of one captured frame (proto CaptureLayout): one image; or for a multi-view frame a multiView EXR,
// a quilt PNG + its JSON metadata, or one PNG per view.
std::vector<CaptureFile> captureFiles(const gpu::RenderResult& frame, const FrameJob& job, const std::string& stem,
                                      v1::CaptureFormat format, v1::CaptureLayout layout) {
  const bool exr = format == v1::CAPTURE_FORMAT_EXR;
  if (frame.views == 1) return {{stem + (exr ? ".exr" : ".png"), encodeFrame(frame, exr ? FrameEncoding::ExrHalf : FrameEncoding::Png8Srgb)}};
  const gpu::DisplayCamera camera = jobCamera(job);
  if (exr) {
    std::vector<std::string> names;
    for (std::uint32_t v = 0; v < frame.views; ++v) names.push_back("view" + viewSuffix(v, frame.views).substr(2));
    return {{stem + ".exr", cli::encodeMultiViewExr(frame.width, frame.height, frame.rgba, names, cli::ImageFormat::ExrHalf)}};
  }
  if (layout == v1::CAPTURE_LAYOUT_QUILT && !camera.quilt) {
    throw BadRequest("layout", "the views of display '" + job.display->id + "' do not form a quilt; use CAPTURE_LAYOUT_VIEWS");
  }
  if (camera.quilt && layout != v1::CAPTURE_LAYOUT_VIEWS) {
    const QuiltLayout& q = *camera.quilt;
    const std::string quiltStem = stem + formatQuiltName(q.columns, q.rows, q.aspect);
    const std::string meta = gpu::quiltMetadataJson(displayForSession(job.display->config, *job.session), camera);
    return {{quiltStem + ".png", encodeFrame(gpu::singleImage(frame, q), FrameEncoding::Png8Srgb)},
            {quiltStem + ".json", std::vector<std::uint8_t>(meta.begin(), meta.end())}};
  }
  std::vector<CaptureFile> files;
  const std::size_t floats = std::size_t(frame.width) * frame.height * 4;
  for (std::uint32_t v = 0; v < frame.views; ++v) {
    gpu::RenderResult view = frame;
    view.views = 1;
    view.rgba.assign(frame.rgba.begin() + std::ptrdiff_t(v * floats), frame.rgba.begin() + std::ptrdiff_t((v + 1) * floats));
    files.push_back({stem + viewSuffix(v, frame.views) + ".png", encodeFrame(view, FrameEncoding::Png8Srgb)});
  }
  return files;
}

}  // namespace

grpc::Status HolotraceService::RenderFrame(grpc::ServerContext* context, const v1::RenderRequest* request,
                                           grpc::ServerWriter<v1::FramePart>* writer) {
  return guarded([&] {
    const FrameJob job = checkRenderRequest(state_, *request);
    StreamSlot slot(state_);
    if (!renderAndSend(state_, clientKey(*context), job, request->format(), 0, *writer)) {
      throw ClientGone("client closed the stream");
    }
    return grpc::Status::OK;
  });
}

// Frames on a fixed clock (frame k due at start + k/fps). A frame is rendered only when the previous one has been
// written, so a slow client is never queued old frames: it gets the newest, and dropped_frames counts the ticks
// it missed (latest-frame-wins, docs/service.md §4 "Backpressure").
grpc::Status HolotraceService::StreamFrames(grpc::ServerContext* context, const v1::StreamRequest* request,
                                            grpc::ServerWriter<v1::FramePart>* writer) {
  return guarded([&] {
    const double fps = request->frames_per_second();
    if (!(fps > 0.0) || fps > state_.config.limits.maxFramesPerSecond) {
      throw BadRequest("frames_per_second", "must be in (0, " +
                                                std::to_string(state_.config.limits.maxFramesPerSecond) + "]");
    }
    FrameJob job = checkRenderRequest(state_, request->render());
    StreamSlot slot(state_);
    const std::string client = clientKey(*context);
    const auto period = std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(1.0 / fps));
    const auto start = Clock::now();
    std::uint64_t tick = 0, dropped = 0;
    while (!context->IsCancelled()) {
      if (state_.shuttingDown) throw ShuttingDown("holotraced is shutting down");
      job.session = state_.scenes.find(request->render().scene_id());  // picks up UpdateScene
      job.seed = request->render().seed() + static_cast<std::uint32_t>(tick);
      if (!renderAndSend(state_, client, job, request->render().format(), dropped, *writer)) break;
      const auto now = Clock::now();
      const auto due = static_cast<std::uint64_t>((now - start) / period) + 1;  // next tick not yet passed
      dropped = due > tick + 1 ? due - tick - 1 : 0;
      tick = std::max(tick + 1, due);
      waitForTick(state_, *context, start + period * static_cast<Clock::rep>(tick));
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
    if (request->format() != v1::CAPTURE_FORMAT_UNSPECIFIED && request->format() != v1::CAPTURE_FORMAT_PNG &&
        request->format() != v1::CAPTURE_FORMAT_EXR) {
      throw BadRequest("format", "unknown capture format");
    }
    if (!v1::CaptureLayout_IsValid(request->layout())) throw BadRequest("layout", "unknown capture layout");
    FrameJob job = checkRenderRequest(state_, request->render());
    StreamSlot slot(state_);
    const std::string client = clientKey(*context);
    for (std::uint32_t i = 0; i < frames; ++i) {
      if (context->IsCancelled()) throw ClientGone("capture cancelled after " + std::to_string(i) + " files");
      if (state_.shuttingDown) throw ShuttingDown("shutting down after " + std::to_string(i) + " complete files");
      job.seed = request->render().seed() + i;
      const gpu::RenderResult frame = renderFrameJob(state_.worker, client, job);
      for (const CaptureFile& file :
           captureFiles(frame, job, captureStem(request->name(), i), request->format(), request->layout())) {
        state_.outputSink.writeFile(file.name, file.bytes);
        v1::CaptureProgress progress;
        progress.set_frames_done(i + 1);
        progress.set_frames_total(frames);
        progress.set_file(file.name);
        writer->Write(progress);  // a gone client is noticed at the next frame (IsCancelled)
      }
    }
    return grpc::Status::OK;
  });
}

}  // namespace ht::server
