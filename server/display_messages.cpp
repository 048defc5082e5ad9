// display_messages.cpp - see display_messages.h.
#include "server/display_messages.h"

#include "camera_models/lenticular_params.h"
#include "server/frame_job.h"

namespace ht::server {

void fillDisplaySummary(const RegisteredDisplay& display, holotrace::v1::DisplaySummary& out) {
  out.set_id(display.id);
  out.set_name(display.config.name);
  out.set_model(std::string(displayModelName(display.config.model)));
  const gpu::FrameShape shape = displayFrameShape(display);
  out.set_panel_width(shape.width);
  out.set_panel_height(shape.height);
  out.set_views(shape.views);
  out.set_source(display.source);
  out.set_serial(display.serial);
}

void fillDisplay(const RegisteredDisplay& display, holotrace::v1::Display& out) {
  fillDisplaySummary(display, *out.mutable_summary());
  out.set_description(display.config.description);
  out.set_calibration_json(display.sourceText);
  out.set_default_spp(display.config.spp);
  if (!display.config.calibration) return;
  const LookingGlassCalibration& c = *display.config.calibration;
  out.set_subpixel_bgr(c.flipSubp);
  auto* optics = out.mutable_optics();
  optics->set_pitch(c.pitch);
  optics->set_slope(c.slope);
  optics->set_center(c.center);
  optics->set_view_cone_deg(c.viewCone);
  optics->set_dpi(static_cast<std::uint32_t>(c.DPI));
}

}  // namespace ht::server
