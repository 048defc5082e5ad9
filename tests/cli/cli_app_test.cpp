// cli_app_test.cpp - `holotrace` in-process: help, version, usage errors and their exit codes. Nothing here
// reaches the GPU: every case fails or finishes before a Vulkan context is created.
#include "cli/cli_app.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <vector>

namespace ht::cli {
namespace {

using ::testing::HasSubstr;
using ::testing::StartsWith;

struct CliRun {
  int code;
  std::string out, err;
};

CliRun run(std::vector<std::string> args) {
  std::ostringstream out, err;
  const int code = runCli(args, out, err);
  return {code, out.str(), err.str()};
}

TEST(CliApp, UnknownRenderOptionExitsTwoWithTheExactMessage) {
  const CliRun r = run({"render", "--spq", "4"});
  EXPECT_EQ(r.code, kExitUsage);
  EXPECT_EQ(r.err, "holotrace render: unknown option '--spq' (see holotrace render --help)\n");
  EXPECT_EQ(r.out, "");
}

TEST(CliApp, BadValuesAreUsageErrors) {
  EXPECT_THAT(run({"render", "--spp", "zero"}).err,
              HasSubstr("option '--spp' = 'zero': expected an integer in [1, 4096]"));
  EXPECT_EQ(run({"render", "--spp", "0"}).code, kExitUsage);
  EXPECT_THAT(run({"render", "--depth"}).err, HasSubstr("option '--depth' needs a value"));
  EXPECT_THAT(run({"render", "-o", "frame.jpg"}).err, HasSubstr("expected a path ending in .png"));
  EXPECT_THAT(run({"render", "--exr", "frame.png"}).err, HasSubstr("expected a path ending in .exr"));
  EXPECT_THAT(run({"info", "--device", "x"}).err, HasSubstr("holotrace info: option '--device' = 'x'"));
  EXPECT_EQ(run({"info", "--spp", "1"}).code, kExitUsage);
}

TEST(CliApp, UnknownOrMissingCommandExitsTwo) {
  const CliRun unknown = run({"rendr"});
  EXPECT_EQ(unknown.code, kExitUsage);
  EXPECT_EQ(unknown.err, "holotrace: unknown command 'rendr' (see holotrace --help)\n");
  EXPECT_THAT(run({"--frobnicate"}).err, HasSubstr("unknown option '--frobnicate'"));
  const CliRun none = run({});
  EXPECT_EQ(none.code, kExitUsage);
  EXPECT_THAT(none.err, HasSubstr("missing command"));
  EXPECT_EQ(run({"help", "nosuch"}).code, kExitUsage);
}

TEST(CliApp, HelpInEveryFormExitsZero) {
  for (const auto& args : std::vector<std::vector<std::string>>{{"--help"}, {"-h"}, {"help"}}) {
    const CliRun r = run(args);
    EXPECT_EQ(r.code, kExitOk);
    EXPECT_THAT(r.out, HasSubstr("Usage: holotrace <command>"));
    EXPECT_THAT(r.out, HasSubstr("render"));
    EXPECT_THAT(r.out, HasSubstr("info"));
  }
  for (const auto& args : std::vector<std::vector<std::string>>{
           {"render", "--help"}, {"help", "render"}, {"render", "--spp", "2", "-h"}}) {
    const CliRun r = run(args);
    EXPECT_EQ(r.code, kExitOk);
    EXPECT_THAT(r.out, StartsWith("Usage: holotrace render"));
    EXPECT_THAT(r.out, HasSubstr("--no-specialize"));
  }
  EXPECT_THAT(run({"info", "--help"}).out, StartsWith("Usage: holotrace info"));
}

TEST(CliApp, VersionPrintsProjectVersion) {
  const CliRun r = run({"--version"});
  EXPECT_EQ(r.code, kExitOk);
  EXPECT_EQ(r.out, versionText() + "\n");
  EXPECT_THAT(r.out, StartsWith("holotrace "));
}

}  // namespace
}  // namespace ht::cli
