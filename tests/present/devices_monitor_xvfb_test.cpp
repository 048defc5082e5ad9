// devices_monitor_xvfb_test.cpp - the MONITOR column of `holotrace devices`: the display sink's monitor picker over
// a RandR snapshot of a private Xvfb (two monitors, the panel's output carrying a synthetic "LKG-P0001" EDID) names
// the panel's monitor; without an X server the column says "none" and why, and the listing still succeeds.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "present/edid.h"
#include "present/xvfb_server.h"

namespace ht::present {
namespace {

const std::string kPanelConfigFile = std::string(HT_TEST_DATA_DIR) + "/configs/xvfb_panel_96x128.json";

struct DevicesRun {
  int status = -1;
  std::string output;
};

// Runs `holotrace devices args...` (no drives, no USB: only the explicit calibration) with $DISPLAY = `display`.
DevicesRun runDevices(const std::vector<std::string>& args, const std::string& display) {
  const auto log = std::filesystem::temp_directory_path() / ("ht_devmon_" + std::to_string(getpid()) + ".log");
  std::vector<std::string> argv = {HOLOTRACE_EXE, "devices", "--no-drives", "--no-usb"};
  argv.insert(argv.end(), args.begin(), args.end());
  std::vector<char*> cargs;
  for (std::string& a : argv) cargs.push_back(a.data());
  cargs.push_back(nullptr);
  pid_t pid = fork();
  if (pid == 0) {
    FILE* f = std::fopen(log.c_str(), "w");
    if (f) {
      dup2(fileno(f), STDOUT_FILENO);
      dup2(fileno(f), STDERR_FILENO);
    }
    if (display.empty())
      unsetenv("DISPLAY");
    else
      setenv("DISPLAY", display.c_str(), 1);
    execv(cargs[0], cargs.data());
    _exit(127);
  }
  int status = 0;
  waitpid(pid, &status, 0);
  std::ifstream in(log);
  std::stringstream text;
  text << in.rdbuf();
  std::filesystem::remove(log);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : 128, text.str()};
}

// The tiny panel's visual.json (its config embeds it) as a file of its own, as a user's --calibration would be.
std::filesystem::path panelCalibrationFile() {
  std::ifstream in(kPanelConfigFile);
  const nlohmann::json config = nlohmann::json::parse(in);
  const auto file = std::filesystem::temp_directory_path() / ("ht_devmon_" + std::to_string(getpid()) + ".json");
  std::ofstream(file) << config["calibration"].dump();
  return file;
}

TEST(DevicesMonitorXvfb, TheMonitorColumnNamesTheLkgMonitor) {
  XvfbServer xvfb(256, 128);
  xvfb.setEdid("screen", makeEdid("LKG-P0001"));
  xvfb.setMonitor("MAIN", {0, 0, 160, 128}, {});
  xvfb.setMonitor("LKG-P", {160, 0, 96, 128}, {"screen"});
  const auto calibration = panelCalibrationFile();

  const DevicesRun table = runDevices({"--calibration", calibration.string()}, xvfb.display());
  EXPECT_EQ(table.status, 0) << table.output;
  EXPECT_NE(table.output.find("MONITOR"), std::string::npos) << table.output;
  EXPECT_NE(table.output.find("LKG-P0001     "), std::string::npos) << table.output;
  EXPECT_NE(table.output.find(" LKG-P "), std::string::npos) << table.output;
  EXPECT_EQ(table.output.find("monitor:"), std::string::npos) << table.output;

  const DevicesRun json =
      runDevices({"--calibration", calibration.string(), "--json", "--x-display", xvfb.display()}, "");
  ASSERT_EQ(json.status, 0) << json.output;
  const nlohmann::json line = nlohmann::json::parse(json.output);
  EXPECT_EQ(line["monitor"], "LKG-P");
  EXPECT_EQ(line["monitor_problem"], "");
  std::filesystem::remove(calibration);
}

TEST(DevicesMonitorXvfb, WithoutAnXServerTheColumnSaysWhy) {
  const auto calibration = panelCalibrationFile();
  const DevicesRun unset = runDevices({"--calibration", calibration.string()}, "");
  EXPECT_EQ(unset.status, 0) << unset.output;
  EXPECT_NE(unset.output.find(" none "), std::string::npos) << unset.output;
  EXPECT_NE(unset.output.find("monitor: no X display given and $DISPLAY is not set"), std::string::npos)
      << unset.output;

  const DevicesRun gone = runDevices({"--calibration", calibration.string(), "--json"}, ":9876");
  ASSERT_EQ(gone.status, 0) << gone.output;
  const nlohmann::json line = nlohmann::json::parse(gone.output);
  EXPECT_EQ(line["monitor"], "");
  EXPECT_NE(line["monitor_problem"].get<std::string>().find("cannot connect to X display ':9876'"), std::string::npos)
      << gone.output;
  std::filesystem::remove(calibration);
}

}  // namespace
}  // namespace ht::present
