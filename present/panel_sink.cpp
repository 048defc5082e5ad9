// panel_sink.cpp - the present thread: attach (X, RandR, picker, window, swapchain), serve frames from the mailbox,
// watch RandR, detach on loss and attach again (panel_sink.h).
#include "present/panel_sink.h"

#include <xcb/randr.h>

#include <atomic>
#include <cstdio>
#include <mutex>
#include <thread>

#include "gpu/vulkan_context.h"
#include "present/frame_mailbox.h"
#include "present/randr_reader.h"

namespace ht::present {
namespace {

constexpr std::chrono::milliseconds kPollInterval{20};  // X events and stop requests are seen this often

double millisecondsSince(Clock::time_point start, Clock::time_point end) {
  return std::chrono::duration<double, std::milli>(end - start).count();
}

// Everything that lives while the sink is attached; members are destroyed in reverse order (swapchain before the
// window before the connection).
struct Attachment {
  std::unique_ptr<XConnection> x;
  std::uint8_t randrEventBase = 0;
  PickedMonitor monitor;
  std::unique_ptr<XWindow> window;
  std::unique_ptr<SwapchainPresenter> presenter;
};

}  // namespace

struct PanelSink::State {
  PanelSinkOptions options;
  FrameMailbox mailbox;
  mutable std::mutex mutex;  // guards stats and window
  PanelSinkStats stats;
  std::uint32_t window = XCB_NONE;
  std::atomic<bool> stopping{false};
  std::unique_ptr<gpu::VulkanContext> context;
  FrameMailbox::FramePtr last;  // the frame on the panel (present thread only)
  std::thread thread;

  void log(const std::string& line) const {
    if (options.log)
      options.log(line);
    else
      std::fprintf(stderr, "holotrace panel: %s\n", line.c_str());
  }
  void run();
  void attach(Attachment& a);
  void noteDetached(const std::string& reason);
  void waitDetached();
  std::string serve(Attachment& a);
  std::string showFrame(Attachment& a, const PanelFrame& frame, bool fresh);
  std::string checkMonitor(Attachment& a);
  bool fitsPanel(const Attachment& a, const PanelFrame& frame);
};

// A frame of another size than the panel is a caller's mistake, not a reason to detach: it is dropped and logged.
bool PanelSink::State::fitsPanel(const Attachment& a, const PanelFrame& frame) {
  if (frame.width == a.monitor.rect.width && frame.height == a.monitor.rect.height) return true;
  const std::string problem = "frame " + std::to_string(frame.sequence) + " is " + std::to_string(frame.width) + "x" +
                              std::to_string(frame.height) + ", the panel " + describeRect(a.monitor.rect) +
                              "; not shown";
  std::lock_guard lock(mutex);
  if (stats.lastError != problem) log(problem);
  stats.lastError = problem;
  return false;
}

void PanelSink::State::run() {
  try {
    context = std::make_unique<gpu::VulkanContext>(gpu::VulkanContext::Options{options.vulkanDevice, false, true});
  } catch (const Error& e) {
    noteDetached(std::string("no Vulkan device for presenting: ") + e.what());
    return;
  }
  while (!stopping) {
    Attachment a;
    try {
      attach(a);
    } catch (const Error& e) {
      noteDetached(e.what());
      waitDetached();
      continue;
    }
    std::string reason = serve(a);
    {
      std::lock_guard lock(mutex);
      window = XCB_NONE;
    }
    a.presenter.reset();
    a.window.reset();
    if (!stopping) noteDetached(reason);
  }
  context.reset();
}

void PanelSink::State::attach(Attachment& a) {
  a.x = std::make_unique<XConnection>(options.xDisplay);
  a.randrEventBase = selectRandrEvents(*a.x);
  a.monitor = pickMonitor(readRandrSnapshot(*a.x), options.panel);
  a.window = std::make_unique<XWindow>(*a.x, a.monitor.rect, options.window);
  a.presenter =
      std::make_unique<SwapchainPresenter>(*context, *a.x, a.window->id(), options.presentMode, options.transfer);
  std::lock_guard lock(mutex);
  window = a.window->id();
  stats.attached = true;
  stats.monitor = a.monitor;
  stats.swapchain = a.presenter->info();
  ++stats.attachments;
  stats.lastError.clear();
  log("showing frames on monitor " + a.monitor.monitor + " " + describeRect(a.monitor.rect) + " of X display '" +
      a.x->name() + "' (" + a.monitor.rule + (a.monitor.edidName.empty() ? "" : ", EDID '" + a.monitor.edidName + "'") +
      ", " + a.presenter->info().presentMode + ", " + a.presenter->info().format + ", " + a.presenter->info().transfer +
      ")");
}

void PanelSink::State::noteDetached(const std::string& reason) {
  std::lock_guard lock(mutex);
  const bool changed = stats.attached || stats.lastError != reason;
  stats.attached = false;
  stats.monitor.reset();
  stats.swapchain = {};
  stats.lastError = reason;
  if (changed)
    log("not showing frames: " + reason + " (retrying every " + std::to_string(options.retryInterval.count()) + " ms)");
}

// Detached: keep taking frames (the newest becomes the one shown on re-attach) until it is time to retry.
void PanelSink::State::waitDetached() {
  const auto until = Clock::now() + options.retryInterval;
  while (!stopping && Clock::now() < until) {
    if (auto frame = mailbox.take(kPollInterval)) last = std::move(frame);
  }
}

std::string PanelSink::State::checkMonitor(Attachment& a) {
  try {
    PickedMonitor now = pickMonitor(readRandrSnapshot(*a.x), options.panel);
    if (now == a.monitor) return "";
    return "the panel changed from " + a.monitor.monitor + " " + describeRect(a.monitor.rect) + " to " + now.monitor +
           " " + describeRect(now.rect);
  } catch (const Error& e) { return e.what(); }
}

std::string PanelSink::State::showFrame(Attachment& a, const PanelFrame& frame, bool fresh) {
  const auto start = Clock::now();
  PresentOutcome outcome;
  try {
    outcome = a.presenter->present(frame);
  } catch (const Error& e) { return e.what(); }
  const auto end = Clock::now();
  if (outcome == PresentOutcome::SurfaceLost) return "the panel window's Vulkan surface was lost";
  if (outcome == PresentOutcome::Timeout) return "";  // the frame stays `last` and is shown on the next chance
  std::lock_guard lock(mutex);
  ++stats.presented;
  stats.lastPresentedSequence = frame.sequence;
  stats.lastPresentCallMs = millisecondsSince(start, end);
  if (fresh) stats.lastPresentLatencyMs = millisecondsSince(frame.done, end);
  stats.swapchain = a.presenter->info();
  return "";
}

// Attached: show new frames, re-show the last one when the window needs it, watch RandR and the connection.
std::string PanelSink::State::serve(Attachment& a) {
  bool reshow = last != nullptr;
  auto nextCheck = Clock::now() + options.recheckInterval;
  while (!stopping) {
    bool randrChanged = false;
    while (xcb_generic_event_t* event = xcb_poll_for_event(a.x->get())) {
      const std::uint8_t type = event->response_type & 0x7F;
      if (type == a.randrEventBase + XCB_RANDR_SCREEN_CHANGE_NOTIFY || type == a.randrEventBase + XCB_RANDR_NOTIFY) {
        randrChanged = true;
      }
      if (type == XCB_EXPOSE) reshow = true;
      std::free(event);
    }
    if (!a.x->alive()) return "the connection to X display '" + a.x->name() + "' closed (X server gone)";
    if (randrChanged || Clock::now() >= nextCheck) {
      if (std::string moved = checkMonitor(a); !moved.empty()) return moved;
      nextCheck = Clock::now() + options.recheckInterval;
    }
    auto frame = mailbox.take(kPollInterval);
    if (frame && !fitsPanel(a, *frame)) frame.reset();  // refused, logged; the panel keeps the last good frame
    std::string problem;
    if (frame) {
      last = std::move(frame);
      problem = showFrame(a, *last, true);
      reshow = false;
    } else if (reshow && last) {
      problem = showFrame(a, *last, false);
      reshow = false;
    }
    if (!problem.empty()) return problem;
  }
  return "stopped";
}

PanelSink::PanelSink(PanelSinkOptions options) : state_(std::make_unique<State>()) {
  state_->options = std::move(options);
  state_->thread = std::thread([s = state_.get()] { s->run(); });
}

PanelSink::~PanelSink() {
  state_->stopping = true;
  state_->mailbox.close();
  state_->thread.join();
}

std::uint64_t PanelSink::submit(PanelFrame frame) { return state_->mailbox.put(std::move(frame)); }

PanelSinkStats PanelSink::stats() const {
  std::lock_guard lock(state_->mutex);
  PanelSinkStats s = state_->stats;
  s.submitted = state_->mailbox.submitted();
  s.dropped = state_->mailbox.dropped();
  return s;
}

std::uint32_t PanelSink::windowId() const {
  std::lock_guard lock(state_->mutex);
  return state_->window;
}

}  // namespace ht::present
