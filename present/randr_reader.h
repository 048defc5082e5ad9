// randr_reader.h - a RandrSnapshot (randr_snapshot.h) read from a live X server with xcb-randr (RandR 1.5 monitors,
// outputs, CRTCs, EDID properties, CRTC transforms), and the notifications that say it changed.
#pragma once
#include "present/randr_snapshot.h"
#include "present/x_connection.h"

namespace ht::present {

// Throws PresentError when the server lacks RandR 1.5 or a request fails.
RandrSnapshot readRandrSnapshot(const XConnection& x);

// Asks the server to send RandR change events (screen change, output/CRTC change) for the root window; returns the
// first event code of the RandR extension (event codes are relative to it).
std::uint8_t selectRandrEvents(const XConnection& x);

}  // namespace ht::present
