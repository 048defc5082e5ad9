// fuzz_quilt_name.cpp - libFuzzer target: the quilt file-name tag parser (camera_models/quilt_layout.h).
//
// Besides "no crash, only ConfigError", it checks a property: a name that parses formats back
// (formatQuiltName) to a tag that parses to the same columns, rows and aspect bits. A mismatch aborts.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string_view>

#include "camera_models/quilt_layout.h"
#include "common/error.h"

namespace {

void checkRoundTrip(const ht::QuiltName& name) {
  if (!name.aspect) return;
  const std::string formatted = ht::formatQuiltName(name.columns, name.rows, *name.aspect);
  ht::QuiltName again;
  try {
    again = ht::parseQuiltName(formatted);
  } catch (const ht::ConfigError& e) {
    std::fprintf(stderr, "formatQuiltName wrote '%s', which parseQuiltName refuses: %s\n", formatted.c_str(), e.what());
    std::abort();
  }
  if (again.columns != name.columns || again.rows != name.rows || !again.aspect || *again.aspect != *name.aspect) {
    std::fprintf(stderr, "quilt name round trip changed the values: '%s' (aspect %.17g)\n", formatted.c_str(),
                 *name.aspect);
    std::abort();
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    checkRoundTrip(ht::parseQuiltName(text));
  } catch (const ht::ConfigError&) {}
  return 0;
}
