// request_checks.cpp - see request_checks.h.
#include "server/request_checks.h"

#include "common/error.h"
#include "server/path_rules.h"

namespace ht::server {

StreamSlot::StreamSlot(ServiceState& state) : state_(state) {
  const std::uint32_t before = state_.activeStreams.fetch_add(1);
  if (before >= state_.config.limits.maxClients) {
    state_.activeStreams.fetch_sub(1);
    throw LimitExceeded("all " + std::to_string(state_.config.limits.maxClients) +
                        " streaming slots are busy (limits.max_clients)");
  }
}

StreamSlot::~StreamSlot() { state_.activeStreams.fetch_sub(1); }

FrameEncoding checkPixelFormat(holotrace::v1::PixelFormat format) {
  switch (format) {
    case holotrace::v1::PIXEL_FORMAT_UNSPECIFIED:
    case holotrace::v1::PIXEL_FORMAT_RGBA8: return FrameEncoding::Rgba8Srgb;
    case holotrace::v1::PIXEL_FORMAT_RGBA16F: return FrameEncoding::Rgba16fLinear;
    case holotrace::v1::PIXEL_FORMAT_PNG: return FrameEncoding::Png8Srgb;
    default: throw BadRequest("render.format", "unknown pixel format " + std::to_string(format));
  }
}

FrameJob checkRenderRequest(ServiceState& state, const holotrace::v1::RenderRequest& request) {
  const Limits& limits = state.config.limits;
  if (request.display_id().empty()) throw BadRequest("render.display_id", "is empty");
  if (request.scene_id().empty()) throw BadRequest("render.scene_id", "is empty");
  if (request.spp() > limits.maxSpp) {
    throw BadRequest("render.spp",
                     std::to_string(request.spp()) + " exceeds limits.max_spp = " + std::to_string(limits.maxSpp));
  }
  if (request.refine_spp() > limits.maxSpp) {
    throw BadRequest("render.refine_spp", std::to_string(request.refine_spp()) +
                                              " exceeds limits.max_spp = " + std::to_string(limits.maxSpp));
  }
  if (!(request.refine_contrast() >= 0.0f && request.refine_contrast() <= 1.0f)) {
    throw BadRequest("render.refine_contrast",
                     std::to_string(request.refine_contrast()) + " is not in [0, 1] (0 = the default 0.08)");
  }
  checkPixelFormat(request.format());
  FrameJob job;
  job.display = state.displays.find(request.display_id());
  job.session = state.scenes.find(request.scene_id());
  job.spp = request.spp();
  job.seed = request.seed();
  job.refineSpp = request.refine_spp();
  if (request.refine_contrast() > 0.0f) job.refineContrast = request.refine_contrast();
  job.reuse = request.reuse_after_edits();
  job.path = request.quilt() ? gpu::CameraPath::Quilt : gpu::CameraPath::Native;
  job.cluster = state.cluster;
  gpu::FrameShape shape;
  try {
    shape = displayFrameShape(*job.display, job.path);
  } catch (const ConfigError& e) { throw BadRequest("quilt", e.expected()); }
  const std::uint64_t pixels = std::uint64_t(shape.width) * shape.height * shape.views;
  if (pixels > limits.maxPanelPixels) {
    throw LimitExceeded("display '" + request.display_id() + "' is " + std::to_string(shape.views) + " x " +
                        std::to_string(shape.width) + "x" + std::to_string(shape.height) +
                        " pixels (limits.max_panel_pixels = " + std::to_string(limits.maxPanelPixels) + ")");
  }
  return job;
}

}  // namespace ht::server
