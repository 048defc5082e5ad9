// wall_command.h - `holotrace wall`: live wall mode under mpirun (docs/CLUSTER.md §7). Each rank renders its own
// group of projectors' views of every frame (wall_layout.h), presents them through its own display sink, and all
// ranks flip together behind the swap barrier (cluster/wall_loop.h); per-rank render / barrier wait / present times,
// the barrier's cost, the flip skew and the late ranks are reported at the end.
#pragma once
#include <ostream>
#include <span>
#include <string>

namespace ht::cli {

int runWall(std::span<const std::string> args, std::ostream& out);
std::string wallHelp();

}  // namespace ht::cli
