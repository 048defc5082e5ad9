// monitor_lookup.cpp - see monitor_lookup.h.
#include "present/monitor_lookup.h"

#include "present/randr_reader.h"
#include "present/x_connection.h"

namespace ht::present {

MonitorLookup::MonitorLookup(std::string xDisplay) : xDisplay_(std::move(xDisplay)) {}

MonitorLookupResult MonitorLookup::find(const PanelRequest& request) {
  if (!read_) {
    read_ = true;
    try {
      XConnection x(xDisplay_);
      snapshot_ = readRandrSnapshot(x);
    } catch (const Error& e) { xProblem_ = e.what(); }
  }
  if (!snapshot_) return {std::nullopt, xProblem_};
  try {
    return {pickMonitor(*snapshot_, request), ""};
  } catch (const PresentError& e) { return {std::nullopt, e.what()}; }
}

}  // namespace ht::present
