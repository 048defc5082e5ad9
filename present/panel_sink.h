// panel_sink.h - a display sink: frames onto one panel, from a present thread of its own.
//
// submit() stores the frame in a one-slot mailbox and returns at once (rendering never waits on the display; a frame
// replaced before it was shown counts as dropped). The present thread attaches to the panel (X connection, RandR
// snapshot, monitor picker, window, swapchain), shows the newest frame, and keeps the last frame up when no new one
// comes. When the monitor, the window or the X server goes away it logs, detaches and tries again every
// `retryInterval`; when the panel is back it re-attaches and shows the last frame again. RandR change notifications
// (and a periodic re-check) re-run the monitor picker: a panel that moved or changed mode is re-attached.
//
// The sink renders nothing itself and never blocks the caller; stats() is safe from any thread.
#pragma once
#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "present/monitor_picker.h"
#include "present/panel_frame.h"
#include "present/swapchain_presenter.h"
#include "present/x_window.h"

namespace ht::present {

struct PanelSinkOptions {
  std::string xDisplay;  // ":0"; "" = $DISPLAY
  PanelRequest panel;    // screen size + optional output name / geometry
  WindowMode window = WindowMode::OverrideRedirect;
  PresentModeChoice presentMode = PresentModeChoice::Auto;
  // Copy when the surface allows it, else storage write; ForceStorageWrite tests the storage path where a copy works
  // (holotrace show and holotraced take it from HOLOTRACE_PANEL_TRANSFER=storage, frame_transfer.h).
  FrameTransferChoice transfer = FrameTransferChoice::Auto;
  int vulkanDevice = -1;                            // --device; -1 automatic
  std::chrono::milliseconds retryInterval{1000};    // between attach attempts while detached
  std::chrono::milliseconds recheckInterval{1000};  // re-run the monitor picker while attached
  std::function<void(const std::string&)> log;      // one line per state change; default: stderr
};

struct PanelSinkStats {
  bool attached = false;
  std::optional<PickedMonitor> monitor;     // where the frames go (while attached)
  SwapchainInfo swapchain;                  // size, present mode, format (while attached)
  std::uint64_t submitted = 0;              // frames given to submit()
  std::uint64_t presented = 0;              // frames queued for display (a re-shown frame counts again)
  std::uint64_t dropped = 0;                // frames replaced in the mailbox before they were shown
  std::uint64_t lastPresentedSequence = 0;  // submit order of the frame on the panel (1, 2, ...)
  double lastPresentLatencyMs = 0.0;        // frame done -> vkQueuePresentKHR returned, for the last frame shown
  double lastPresentCallMs = 0.0;           // the present call itself (upload + copy + present)
  std::uint32_t attachments = 0;            // successful attaches (1 + re-attaches)
  std::string lastError;                    // why the sink is (or last was) detached; "" if never
};

class PanelSink {
 public:
  explicit PanelSink(PanelSinkOptions options);  // starts the present thread
  ~PanelSink();                                  // stops it, closes the window
  PanelSink(const PanelSink&) = delete;
  PanelSink& operator=(const PanelSink&) = delete;

  // Never blocks on presentation. Returns the frame's sequence number.
  std::uint64_t submit(PanelFrame frame);
  PanelSinkStats stats() const;
  // The panel window's X id while attached (tests read its geometry); XCB_NONE otherwise.
  std::uint32_t windowId() const;

  struct State;

 private:
  std::unique_ptr<State> state_;
};

}  // namespace ht::present
