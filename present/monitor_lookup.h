// monitor_lookup.h - "which monitor shows this panel?" for listings such as `holotrace devices`: one RandR snapshot
// of an X display, read on first use, and the pure monitor picker (monitor_picker.h) run over it for each panel.
// No X server, no RandR, or a picker refusal is an answer (`problem` says why), never an exception: a listing must
// work on a headless host too.
#pragma once
#include <optional>
#include <string>

#include "present/monitor_picker.h"

namespace ht::present {

struct MonitorLookupResult {
  std::optional<PickedMonitor> monitor;
  std::string problem;  // why `monitor` is empty ("" when it is set)
};

class MonitorLookup {
 public:
  explicit MonitorLookup(std::string xDisplay);  // "" = $DISPLAY; nothing is opened until find()

  MonitorLookupResult find(const PanelRequest& request);

 private:
  std::string xDisplay_;
  bool read_ = false;
  std::optional<RandrSnapshot> snapshot_;
  std::string xProblem_;  // why there is no snapshot
};

}  // namespace ht::present
