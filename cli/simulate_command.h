// simulate_command.h - `holotrace simulate`: what an eye in front of a light-field display sees of a rendered panel
// (or projector images, or LCD image), through the display's own optics model (camera_models/simulated_view.h,
// docs/OPTICS.md §12); one eye, or a strip of eyes across the view cone.
#pragma once
#include <ostream>
#include <span>
#include <string>

namespace ht::cli {

int runSimulate(std::span<const std::string> args, std::ostream& out);
std::string simulateHelp();

}  // namespace ht::cli
