// panel_feed.cpp - see panel_feed.h.
#include "server/panel_feed.h"

#include "server/errors.h"
#include "server/panel_sinks.h"

namespace ht::server {
namespace {

std::string shapeText(const gpu::FrameShape& shape) {
  return std::to_string(shape.width) + "x" + std::to_string(shape.height) +
         (shape.views > 1 ? " x " + std::to_string(shape.views) + " views" : "");
}

}  // namespace

present::PanelFrame panelFrameOf(const gpu::RenderResult& frame, const FrameJob& job,
                                 const std::vector<std::uint8_t>* rgba8) {
  const DisplayConfig display = displayForSession(job.display->config, *job.session);
  const frame_io::FrameImages images{frame.width, frame.height, frame.views, frame.rgba};
  const frame_io::FrameDisplay panel{display, jobCamera(job).quilt};
  if (rgba8 && present::panelImageIsTheFrame(images, panel)) return present::panelFrameFromRgba8(images, *rgba8);
  return present::panelFrame(images, panel);
}

std::shared_ptr<present::PanelSink> streamPanelSink(const ServiceState& state, const std::string& displayId,
                                                    const FrameJob& job) {
  std::shared_ptr<const RegisteredDisplay> target;
  try {
    target = state.displays.find(displayId);
  } catch (const UnknownDisplay& e) { throw BadRequest("present_on", e.what()); }
  std::shared_ptr<present::PanelSink> sink = state.panels ? state.panels->find(displayId) : nullptr;
  if (!sink) {
    throw NoPanelSink("present_on: display '" + displayId +
                      "' has no panel sink; list it in the daemon config's \"present\" (docs/SERVICE.md §11) and "
                      "restart or send SIGHUP");
  }
  const gpu::FrameShape streamed = displayFrameShape(*job.display, job.path);
  const gpu::FrameShape panel = displayFrameShape(*target);
  if (streamed.views != 1 || streamed.width != panel.width || streamed.height != panel.height) {
    throw BadRequest("present_on", "the streamed frame of display '" + job.display->id + "' is " + shapeText(streamed) +
                                       ", the panel of '" + displayId + "' shows " + shapeText(panel) +
                                       " (stream that panel's display, without quilt)");
  }
  return sink;
}

}  // namespace ht::server
