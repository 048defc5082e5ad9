// raycast_command.h - `holotrace raycast`: trace a user's ray batch against a scene on the GPU and write the
// hits (closest hit, or occlusion with --any). File formats: cli/rays_file.h.
#pragma once
#include <ostream>
#include <span>
#include <string>

namespace ht::cli {

std::string raycastHelp();
int runRaycast(std::span<const std::string> args, std::ostream& out);

}  // namespace ht::cli
