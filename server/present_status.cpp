// present_status.cpp - see present_status.h.
#include "server/present_status.h"

#include "server/panel_sinks.h"
#include "server/service_state.h"

namespace ht::server {

void fillPanelStatus(const std::string& displayId, const present::PanelSinkStats& stats, const std::string& xDisplay,
                     holotrace::v1::PanelStatus& out) {
  out.set_display_id(displayId);
  out.set_attached(stats.attached);
  if (stats.monitor) {
    out.set_monitor(stats.monitor->monitor);
    out.set_output(stats.monitor->output);
    out.set_edid_name(stats.monitor->edidName);
    out.set_geometry(present::describeRect(stats.monitor->rect));
    out.set_refresh_hz(stats.monitor->refreshHz);
  }
  out.set_present_mode(stats.swapchain.presentMode);
  out.set_transfer(stats.swapchain.transfer);
  out.set_submitted(stats.submitted);
  out.set_presented(stats.presented);
  out.set_dropped(stats.dropped);
  out.set_last_present_latency_ms(stats.lastPresentLatencyMs);
  out.set_last_error(stats.lastError);
  out.set_attachments(stats.attachments);
  out.set_x_display(xDisplay);
}

void addPanelStatuses(const ServiceState& state, holotrace::v1::StatusResponse& response) {
  if (!state.panels) return;
  for (const auto& [id, stats] : state.panels->stats()) {
    fillPanelStatus(id, stats, state.panels->xDisplay(), *response.add_panels());
  }
}

}  // namespace ht::server
