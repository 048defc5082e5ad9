// input_hardening_test.cpp - issue 14 (hostile input) without a GPU: JSON nesting in the daemon config and the
// displays directory, display ids that would shadow builtins.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <sstream>
#include <string>

#include "common/error.h"
#include "server/daemon_config.h"
#include "server/display_registry.h"
#include "tests/server/server_fixture.h"

namespace ht::server::test {
namespace {

using ::testing::HasSubstr;

std::string deepArray(std::size_t depth) { return std::string(depth, '[') + std::string(depth, ']'); }

// Item 2: a daemon config nested 100,000 levels deep crashed holotraced at start (stack overflow in dump()).
TEST(InputHardeningTest, DeeplyNestedDaemonConfigIsAConfigError) {
  for (const std::string& text :
       {deepArray(100000), R"({"scene_root": "s", "output_root": "o", "listen": )" + deepArray(100000) + "}"}) {
    try {
      parseDaemonConfig(text, "deep.json", "/");
      FAIL() << "accepted a deeply nested config";
    } catch (const ConfigError& e) {
      EXPECT_EQ(e.file(), "deep.json");
      EXPECT_THAT(e.expected(), HasSubstr("JSON nesting deeper than 64 levels"));
    }
  }
}

// Item 2: the same file in the displays directory killed the daemon at start and on SIGHUP; now it is logged and
// skipped like any bad file, and the good ones next to it load.
TEST(InputHardeningTest, DeeplyNestedDisplayFileIsLoggedAndSkipped) {
  TempDir dir;
  writeText(dir.path / "deep.json", deepArray(100000));
  writeText(dir.path / "tiny.json", tinyDisplayJson());
  DisplayRegistry registry(dir.path);
  for (int reload = 0; reload < 2; ++reload) {  // start, then SIGHUP
    std::ostringstream log;
    registry.reload(log);
    EXPECT_THAT(log.str(), HasSubstr("deep.json: field '(json)' = line 1, column 65"));
    EXPECT_NO_THROW(registry.find("tiny"));
    EXPECT_THROW(registry.find("deep"), UnknownDisplay);
  }
}

// Item 10: a file named builtin:portrait.json in the displays directory replaced the builtin Portrait.
TEST(InputHardeningTest, ADisplayFileCannotShadowABuiltin) {
  TempDir dir;
  writeText(dir.path / "builtin:portrait.json", tinyDisplayJson());
  DisplayRegistry registry(dir.path);
  std::ostringstream log;
  registry.reload(log);
  EXPECT_THAT(log.str(), HasSubstr("reserved for the builtin displays"));
  EXPECT_EQ(registry.find("builtin:portrait")->config.sourcePath, "builtin:portrait");
}

}  // namespace
}  // namespace ht::server::test
