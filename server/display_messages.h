// display_messages.h - RegisteredDisplay -> protocol messages.
#pragma once
#include "holotrace/v1/holotrace.pb.h"
#include "server/display_registry.h"

namespace ht::server {

void fillDisplaySummary(const RegisteredDisplay& display, holotrace::v1::DisplaySummary& out);
void fillDisplay(const RegisteredDisplay& display, holotrace::v1::Display& out);

}  // namespace ht::server
