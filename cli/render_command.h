// render_command.h - `holotrace render`: display + scene -> BVH -> GPU frame -> PNG/EXR.
#pragma once
#include <ostream>
#include <span>
#include <string>

#include "cli/render_options.h"

namespace ht::cli {

int runRender(std::span<const std::string> args, std::ostream& out);

}  // namespace ht::cli
