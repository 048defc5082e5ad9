// present_status.h - a panel sink's state as the protocol's PanelStatus, and the panels part of Status.
#pragma once
#include <string>

#include "holotrace/v1/holotrace.pb.h"
#include "present/panel_sink.h"

namespace ht::server {

struct ServiceState;

void fillPanelStatus(const std::string& displayId, const present::PanelSinkStats& stats, const std::string& xDisplay,
                     holotrace::v1::PanelStatus& out);

// Appends one PanelStatus per panel sink of the daemon (none when "present" is off).
void addPanelStatuses(const ServiceState& state, holotrace::v1::StatusResponse& response);

}  // namespace ht::server
