// swapchain_presenter.h - a Vulkan swapchain on an X window (VK_KHR_xcb_surface) that shows PanelFrames.
//
// - Present mode: MAILBOX when the surface offers it (a newer frame replaces a queued one, no tearing), else FIFO (the
//   only mode every driver has); the sink feeds it from its one-slot mailbox with at most one frame in flight.
// - Format: an 8-bit UNORM format (B8G8R8A8 or R8G8B8A8) in the SRGB_NONLINEAR colour space. The frame's bytes are
//   already sRGB-encoded (the PNG's bytes), and a copy moves bytes unchanged, so a UNORM image holds exactly them and
//   the display decodes them as sRGB. (An _SRGB image would hold the same bytes after a copy, but a shader or blit
//   writing to it would encode a second time; UNORM keeps every path right.) An _SRGB format is used only if the
//   surface offers no UNORM one.
// - Transfer (frame_transfer.h): the frame goes from a host-visible staging buffer into the swapchain image with
//   vkCmdCopyBufferToImage when the surface's supportedUsageFlags have TRANSFER_DST, else (or when forced) with a
//   compute shader's storage write; a surface allowing neither is refused with a PresentError naming the flags.
// - OUT_OF_DATE / SUBOPTIMAL: the swapchain is recreated and the frame shown again. SURFACE_LOST is reported to the
//   caller, which drops the window and re-attaches.
// Not thread-safe: one present thread owns it.
#pragma once
#include <cstdint>
#include <memory>
#include <string>

#include "gpu/vulkan_context.h"
#include "present/frame_transfer.h"
#include "present/panel_frame.h"
#include "present/x_connection.h"

namespace ht::present {

enum class PresentModeChoice { Auto, Fifo };  // Auto: MAILBOX when offered, else FIFO

enum class PresentOutcome {
  Presented,    // the frame was queued for display
  SurfaceLost,  // the window or the X server is gone: drop this presenter and attach again
  Timeout,      // no swapchain image became free in time (the frame stays the caller's)
};

struct SwapchainInfo {
  std::uint32_t width = 0, height = 0, images = 0;
  std::string presentMode;  // "MAILBOX", "FIFO"
  std::string format;       // "B8G8R8A8_UNORM"
  std::string transfer;     // "copy", "storage write"
};

class SwapchainPresenter {
 public:
  // `context` must be created with Options::presentation. Throws PresentError / GpuError.
  SwapchainPresenter(gpu::VulkanContext& context, const XConnection& x, xcb_window_t window, PresentModeChoice mode,
                     FrameTransferChoice transfer = FrameTransferChoice::Auto);
  ~SwapchainPresenter();
  SwapchainPresenter(const SwapchainPresenter&) = delete;
  SwapchainPresenter& operator=(const SwapchainPresenter&) = delete;

  // Shows `frame`, which must be the swapchain's size (else PresentError). Blocks for the copy (under Xvfb the
  // present is a CPU copy too); call it from a present thread only.
  PresentOutcome present(const PanelFrame& frame);
  const SwapchainInfo& info() const;
  std::uint32_t recreations() const;  // swapchains rebuilt after OUT_OF_DATE / SUBOPTIMAL

  struct Impl;

 private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace ht::present
