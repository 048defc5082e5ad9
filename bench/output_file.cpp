// output_file.cpp - see output_file.h.
#include "bench/output_file.h"

#include <filesystem>
#include <fstream>

#include "common/error.h"

namespace ht::bench {

void writeTextFile(const std::string& path, const std::string& text) {
  const std::filesystem::path target(path);
  const std::filesystem::path temp = target.string() + ".tmp";
  std::error_code ec;
  if (target.has_parent_path()) std::filesystem::create_directories(target.parent_path(), ec);
  {
    std::ofstream file(temp, std::ios::binary);
    file << text;
    if (!file.flush()) throw IoError("cannot write " + temp.string());
  }
  std::filesystem::rename(temp, target, ec);
  if (ec) throw IoError("cannot rename " + temp.string() + " to " + path + ": " + ec.message());
}

}  // namespace ht::bench
