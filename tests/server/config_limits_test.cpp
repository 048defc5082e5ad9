// config_limits_test.cpp - holotraced's config values are integers in documented ranges, named when refused
// (never truncated: 0.5 clients, 1e20 clients or a 4 GiB message limit used to become 0), and listen addresses are
// checked as parsed addresses, not by their prefix (issue 14, items 8 and 7).
#include <gtest/gtest.h>

#include <string>

#include "common/error.h"
#include "server/daemon_config.h"
#include "server/listen_address.h"

namespace ht::server::test {
namespace {

// The field a config with `limits` = `limitsJson` is refused for ("" if accepted).
std::string refusedField(const std::string& limitsJson) {
  try {
    parseDaemonConfig(R"({"scene_root": "s", "output_root": "o", "limits": )" + limitsJson + "}", "t.json", "/");
    return "";
  } catch (const ConfigError& e) { return e.field(); }
}

TEST(DaemonConfigLimitsTest, FractionalHugeAndWrappingValuesAreRefusedNamingTheField) {
  EXPECT_EQ(refusedField(R"({"max_clients": 0.5})"), "limits.max_clients");
  EXPECT_EQ(refusedField(R"({"max_clients": 1e20})"), "limits.max_clients");
  EXPECT_EQ(refusedField(R"({"max_clients": 4294967297})"), "limits.max_clients");
  EXPECT_EQ(refusedField(R"({"max_clients": "8"})"), "limits.max_clients");
  EXPECT_EQ(refusedField(R"({"max_message_bytes": 4294967296})"), "limits.max_message_bytes");
  EXPECT_EQ(refusedField(R"({"max_message_bytes": 2147483648})"), "limits.max_message_bytes");  // gRPC takes an int
  EXPECT_EQ(refusedField(R"({"max_spp": 2.5})"), "limits.max_spp");
  EXPECT_EQ(refusedField(R"({"max_frames_in_flight": 0})"), "limits.max_frames_in_flight");
  EXPECT_EQ(refusedField(R"({"max_frames_per_second": 1e-11})"), "limits.max_frames_per_second");
  EXPECT_EQ(refusedField(R"({"max_frames_per_second": 1e12})"), "limits.max_frames_per_second");
  EXPECT_EQ(refusedField(R"({"max_clients": 8, "max_message_bytes": 1048576, "max_frames_per_second": 60})"), "");
  // A budget for uploads in flight smaller than one allowed upload could never admit it.
  EXPECT_EQ(refusedField(R"({"max_scene_bytes": 2000000, "max_upload_bytes_in_flight": 1000000})"),
            "limits.max_upload_bytes_in_flight");
  EXPECT_EQ(refusedField(R"({"scene_idle_seconds": 0, "max_scene_sessions": 10})"), "limits.scene_idle_seconds");
  EXPECT_EQ(refusedField(R"({"max_scene_sessions": 0})"), "limits.max_scene_sessions");
  EXPECT_EQ(refusedField(R"({"max_uploads": 1.5})"), "limits.max_uploads");
  try {
    parseDaemonConfig(R"({"scene_root": "s", "output_root": "o", "limits": {"max_clients": 0.5}})", "t.json", "/");
  } catch (const ConfigError& e) {
    EXPECT_EQ(e.value(), "0.5");
    EXPECT_NE(e.expected().find("integer"), std::string::npos) << e.expected();
  }
}

TEST(DaemonConfigLimitsTest, AcceptedValuesAreExact) {
  const DaemonConfig c = parseDaemonConfig(
      R"({"scene_root": "s", "output_root": "o", "limits": {"max_message_bytes": 2147483647,
          "max_scene_bytes": 1099511627776, "max_upload_bytes_in_flight": 1099511627776,
          "max_frames_per_second": 0.5}})",
      "t.json", "/");
  EXPECT_EQ(c.limits.maxMessageBytes, 2147483647u);
  EXPECT_EQ(c.limits.maxSceneBytes, 1ull << 40);
  EXPECT_EQ(c.limits.maxFramesPerSecond, 0.5);
}

TEST(DaemonConfigLimitsTest, DeviceIsAnIntegerIndex) {
  EXPECT_THROW(parseDaemonConfig(R"({"scene_root": "s", "output_root": "o", "device": "0"})", "t.json", "/"),
               ConfigError);
  EXPECT_THROW(parseDaemonConfig(R"({"scene_root": "s", "output_root": "o", "device": 0.5})", "t.json", "/"),
               ConfigError);
  EXPECT_EQ(parseDaemonConfig(R"({"scene_root": "s", "output_root": "o", "device": 1})", "t.json", "/").deviceIndex, 1);
}

TEST(ListenAddressParseTest, LoopbackIsCheckedOnTheParsedAddress) {
  EXPECT_NO_THROW(checkListenAddress("c", "127.0.0.1:5000"));
  EXPECT_NO_THROW(checkListenAddress("c", "127.5.6.7:65535"));
  EXPECT_NO_THROW(checkListenAddress("c", "[::1]:5000"));
  EXPECT_THROW(checkListenAddress("c", "127.0.0.1.example:5000"), ConfigError);  // a host name, not 127.0.0.1
  EXPECT_THROW(checkListenAddress("c", "127.evil.com:5000"), ConfigError);
  EXPECT_THROW(checkListenAddress("c", "localhost.example:5000"), ConfigError);
  EXPECT_THROW(checkListenAddress("c", "[::1].example:5000"), ConfigError);
  EXPECT_THROW(checkListenAddress("c", "[::ffff:10.0.0.1]:5000"), ConfigError);
  EXPECT_THROW(checkListenAddress("c", "128.0.0.1:5000"), ConfigError);
  EXPECT_THROW(checkListenAddress("c", "127.0.0.1:0"), ConfigError);
  EXPECT_THROW(checkListenAddress("c", "127.0.0.1:65536"), ConfigError);
  EXPECT_THROW(checkListenAddress("c", "127.0.0.1:80x"), ConfigError);
  EXPECT_THROW(checkListenAddress("c", "127.0.0.1"), ConfigError);
}

}  // namespace
}  // namespace ht::server::test
