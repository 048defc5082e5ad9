// rays_command.h - `holotrace rays`: dump the per-(sub)pixel primary rays a display config produces (origin,
// direction, and for lenticular panels the view phase) as an OpenEXR ray table (frame_io/ray_table_exr.h), so a user
// can check a calibration or feed the table to other tools (it reads back as a "ray-table" display).
#pragma once
#include <ostream>
#include <span>
#include <string>

namespace ht::cli {

std::string raysHelp();
int runRays(std::span<const std::string> args, std::ostream& out);

}  // namespace ht::cli
