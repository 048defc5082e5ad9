// capture_command.h - `holotrace capture`: a sequence of frames of one display and scene (frame f rendered with seed
// + f, as the daemon's Capture), written as NAME_fNNNN.png / .exr (+ quilt metadata, per-view files) under --out-dir
// through frame_io's packageFrame. Under mpirun the frames are spread over the ranks (cluster_render.h).
#pragma once
#include <ostream>
#include <span>
#include <string>

namespace ht::cli {

int runCapture(std::span<const std::string> args, std::ostream& out);
std::string captureHelp();

}  // namespace ht::cli
