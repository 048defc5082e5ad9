// panel_feed.h - frames of the render RPCs onto a panel sink (docs/SERVICE.md §11): the panel image of a rendered
// frame (the bytes the file sink's PNG holds) and the checks of a StreamFrames `present_on` target.
#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "gpu/renderer.h"
#include "present/panel_frame.h"
#include "present/panel_sink.h"
#include "server/frame_job.h"
#include "server/service_state.h"

namespace ht::server {

// The panel image of one rendered frame of `job`. `rgba8`: the frame's RGBA8 bytes when the caller has them (a stream
// of that format), copied where they are the panel image instead of encoding the frame a second time.
present::PanelFrame panelFrameOf(const gpu::RenderResult& frame, const FrameJob& job,
                                 const std::vector<std::uint8_t>* rgba8 = nullptr);

// The sink of display `displayId` for frames of `job` (StreamRequest.present_on). Throws BadRequest (unknown id, or
// a panel of another size than the job's frame) or NoPanelSink (a known display without a sink).
std::shared_ptr<present::PanelSink> streamPanelSink(const ServiceState& state, const std::string& displayId,
                                                    const FrameJob& job);

}  // namespace ht::server
