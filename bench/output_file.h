// output_file.h - write a benchmark output file (CSV / JSON) atomically: parent folders are created, the text goes
// to PATH.tmp and is renamed over PATH. Throws ht::IoError naming the path.
#pragma once
#include <string>

namespace ht::bench {

void writeTextFile(const std::string& path, const std::string& text);

}  // namespace ht::bench
