// interleave_command.h - `holotrace interleave`: a quilt image (vendor or holotrace) -> the native panel image of a
// lenticular display, as the Looking Glass shaders interleave it (frame_io/quilt_file.h, docs/OPTICS.md §4.4).
#pragma once
#include <ostream>
#include <span>
#include <string>

namespace ht::cli {

int runInterleave(std::span<const std::string> args, std::ostream& out);
std::string interleaveHelp();

}  // namespace ht::cli
