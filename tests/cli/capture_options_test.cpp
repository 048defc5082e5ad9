// capture_options_test.cpp - `holotrace capture` in-process: its own options and the render options it shares are
// checked before any work, with messages naming `holotrace capture` (nothing here reaches the GPU).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <vector>

#include "cli/cli_app.h"

namespace ht::cli {
namespace {

using ::testing::HasSubstr;

std::pair<int, std::string> capture(std::vector<std::string> args) {
  args.insert(args.begin(), "capture");
  std::ostringstream out, err;
  const int code = runCli(args, out, err);
  return {code, err.str()};
}

TEST(CaptureOptions, OwnAndSharedOptionsAreCheckedWithTheCommandsName) {
  EXPECT_EQ(capture({"--frames", "0"}),
            std::pair(kExitUsage, std::string("holotrace capture: option '--frames' = '0': expected an integer in "
                                              "[1, 1000000] (see holotrace capture --help)\n")));
  EXPECT_THAT(capture({"--format=jpg"}).second, HasSubstr("option '--format' = 'jpg': expected png or exr"));
  EXPECT_THAT(capture({"--name", "a/b"}).second, HasSubstr("option '--name' = 'a/b': expected a file stem"));
  EXPECT_THAT(capture({"--spp", "0"}).second, HasSubstr("holotrace capture: option '--spp' = '0'"));
  EXPECT_THAT(capture({"--bogus"}).second, HasSubstr("holotrace capture: unknown option '--bogus'"));
  for (const char* refused : {"-o", "--exr", "--debug"}) {
    const auto [code, err] = capture({refused, "x"});
    EXPECT_EQ(code, kExitUsage) << refused;
    EXPECT_THAT(err, HasSubstr("is not for captures")) << refused;
  }
}

}  // namespace
}  // namespace ht::cli
