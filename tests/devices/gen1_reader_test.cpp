// gen1_reader_test.cpp - the Gen1 EEPROM reader (devices/gen1_calibration_reader.h) and its page reassembly against
// the in-memory FakeHoloPlay: good reads (whole and split replies, stale replies skipped) and every bad-data fault.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <sstream>

#include "devices/device_error.h"
#include "devices/gen1_calibration_reader.h"
#include "devices/page_assembler.h"
#include "tests/devices/fake_holoplay.h"

namespace ht::devices {
namespace {

using test::eepromImage;
using test::FakeHoloPlay;

std::string fixture(const std::string& name) {
  std::ifstream in(std::string(HT_TEST_DATA_DIR) + "/configs/" + name, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

HidReadOptions fastOptions() {
  HidReadOptions o;
  o.transferTimeout = std::chrono::milliseconds(50);
  o.totalTimeout = std::chrono::milliseconds(2000);
  return o;
}

DeviceFault faultOf(FakeHoloPlay& device, const HidReadOptions& options = fastOptions()) {
  try {
    readGen1Calibration(device, options);
  } catch (const DeviceError& e) {
    EXPECT_EQ(e.device(), "fake HoloPlay");
    EXPECT_NE(std::string(e.what()).find(std::string(deviceFaultName(e.fault()))), std::string::npos) << e.what();
    return e.fault();
  }
  ADD_FAILURE() << "the read succeeded";
  return DeviceFault::Transport;
}

TEST(Gen1Reader, ReadsTheWholeJsonPageByPage) {
  const std::string json = fixture("gen1_8.9_original_visual.json");  // 481 bytes: 8 pages with the prefix
  FakeHoloPlay device(eepromImage(json));
  const LoadedCalibration loaded = readGen1Calibration(device, fastOptions());
  EXPECT_EQ(loaded.json, json);
  EXPECT_EQ(loaded.calibration.serial, "LKG-2K");
  EXPECT_EQ(loaded.calibration.screenW, 2560u);
  EXPECT_EQ(device.requestedPages, (std::vector<std::uint16_t>{0, 1, 2, 3, 4, 5, 6, 7}));
}

TEST(Gen1Reader, JsonEndingExactlyOnAPageBoundaryReadsNoExtraPage) {
  std::string json = fixture("gen1_8.9_user_bare_visual.json");
  json.resize(json.find_last_of('}') + 1);
  // Spaces inside the object until the length prefix + JSON fill whole pages.
  while ((4 + json.size()) % 64 != 0) json.insert(json.size() - 1, " ");
  FakeHoloPlay device(eepromImage(json));
  EXPECT_EQ(readGen1Calibration(device, fastOptions()).json, json);
  EXPECT_EQ(device.requestedPages.size(), (4 + json.size()) / 64);
}

TEST(Gen1Reader, RepliesSplitIntoPartsAreReassembled) {
  const std::string json = fixture("portrait_issue3_visual.json");
  for (std::size_t chunk : {64u, 60u, 17u, 1u}) {
    FakeHoloPlay device(eepromImage(json));
    device.chunkBytes = chunk;
    EXPECT_EQ(readGen1Calibration(device, fastOptions()).json, json) << "chunk " << chunk;
  }
}

TEST(Gen1Reader, StaleRepliesForAnotherPageAreSkipped) {
  const std::string json = fixture("gen1_8.9_original_visual.json");
  FakeHoloPlay device(eepromImage(json));
  device.staleRepliesBefore[0] = 1;
  device.staleRepliesBefore[3] = 3;  // maxRepliesPerPage 4: the fourth reply is the right one
  EXPECT_EQ(readGen1Calibration(device, fastOptions()).json, json);
}

TEST(Gen1Reader, AWrongEchoThatPersistsIsAnEchoMismatch) {
  FakeHoloPlay device(eepromImage(fixture("gen1_8.9_original_visual.json")));
  device.staleRepliesBefore[2] = 4;
  EXPECT_EQ(faultOf(device), DeviceFault::EchoMismatch);
}

TEST(Gen1Reader, AReplyCutShortIsATruncatedReport) {
  FakeHoloPlay device(eepromImage(fixture("gen1_8.9_original_visual.json")));
  device.cutReplyAfter[1] = 40;
  EXPECT_EQ(faultOf(device), DeviceFault::TruncatedReport);
}

TEST(Gen1Reader, NoReplyAtAllIsATimeout) {
  FakeHoloPlay device(eepromImage(fixture("gen1_8.9_original_visual.json")));
  device.cutReplyAfter[0] = 0;
  EXPECT_EQ(faultOf(device), DeviceFault::Timeout);
}

TEST(Gen1Reader, AStalledEndpointIsAStall) {
  FakeHoloPlay device(eepromImage(fixture("gen1_8.9_original_visual.json")));
  device.stallAtPage = 2;
  EXPECT_EQ(faultOf(device), DeviceFault::Stall);
}

TEST(Gen1Reader, ALengthOverTheCapIsRefusedBeforeReadingMore) {
  FakeHoloPlay device(eepromImage("{}", 0x7fffffffu));
  EXPECT_EQ(faultOf(device), DeviceFault::LengthOverCap);
  EXPECT_EQ(device.requestedPages.size(), 1u);
  HidReadOptions small = fastOptions();
  small.maxJsonBytes = 100;
  FakeHoloPlay exact(eepromImage(fixture("gen1_8.9_original_visual.json")));
  EXPECT_EQ(faultOf(exact, small), DeviceFault::LengthOverCap);
}

TEST(Gen1Reader, AnErasedEepromIsAnEmptyCalibration) {
  FakeHoloPlay erased(std::vector<std::uint8_t>(256, 0xff));
  EXPECT_EQ(faultOf(erased), DeviceFault::EmptyCalibration);
  FakeHoloPlay zero(eepromImage("", 0));
  EXPECT_EQ(faultOf(zero), DeviceFault::EmptyCalibration);
}

TEST(Gen1Reader, ALengthBeyondTheEepromDataIsInvalidJson) {
  // The device answers every page; past its data it returns zero bytes, which is no JSON.
  const std::string json = fixture("gen1_8.9_original_visual.json");
  FakeHoloPlay device(eepromImage(json, static_cast<std::uint32_t>(json.size() + 100)));
  EXPECT_EQ(faultOf(device), DeviceFault::InvalidJson);
}

TEST(Gen1Reader, TruncatedJsonIsInvalidJson) {
  const std::string json = fixture("gen1_8.9_original_visual.json");
  FakeHoloPlay device(eepromImage(json.substr(0, 200)));
  EXPECT_EQ(faultOf(device), DeviceFault::InvalidJson);
  FakeHoloPlay array(eepromImage("[1, 2, 3]"));
  EXPECT_EQ(faultOf(array), DeviceFault::InvalidJson);
}

TEST(Gen1Reader, AVisualJsonFailingValidationIsInvalidCalibrationNamingTheField) {
  std::string json = fixture("gen1_8.9_original_visual.json");
  json.replace(json.find("49.825218200683597"), 18, "-1");
  FakeHoloPlay device(eepromImage(json));
  try {
    readGen1Calibration(device, fastOptions());
    FAIL() << "accepted a negative pitch";
  } catch (const DeviceError& e) {
    EXPECT_EQ(e.fault(), DeviceFault::InvalidCalibration);
    EXPECT_NE(std::string(e.what()).find("pitch"), std::string::npos) << e.what();
  }
}

TEST(Gen1Reader, TheWholeReadHasADeadline) {
  FakeHoloPlay device(eepromImage(fixture("gen1_8.9_original_visual.json")));
  HidReadOptions options = fastOptions();
  options.totalTimeout = std::chrono::milliseconds(0);
  EXPECT_EQ(faultOf(device, options), DeviceFault::Timeout);
}

TEST(PageAssembler, CountsPagesFromTheLengthPrefix) {
  PageAssembler pages("dev", 1000);
  std::array<std::uint8_t, 64> page{};
  page[3] = 124;  // 4 + 124 = 128 bytes: two pages
  page[4] = '{';
  pages.addPage(page);
  EXPECT_EQ(pages.pagesNeeded(), 2u);
  EXPECT_FALSE(pages.complete());
  std::array<std::uint8_t, 64> second{};
  second[63] = '}';
  pages.addPage(second);
  ASSERT_TRUE(pages.complete());
  const std::string json = pages.takeJson();
  ASSERT_EQ(json.size(), 124u);
  EXPECT_EQ(json.front(), '{');
  EXPECT_EQ(json.back(), '}');
}

}  // namespace
}  // namespace ht::devices

namespace ht::devices {
namespace {

// The shipped udev rule (configs/udev/) must match the ids the reader opens.
TEST(Gen1UdevRule, MatchesTheVendorProductAndProductString) {
  std::ifstream in(std::string(HT_SOURCE_DIR) + "/configs/udev/70-holotrace-lkg.rules");
  ASSERT_TRUE(in) << "configs/udev/70-holotrace-lkg.rules is missing";
  char vid[8], pid[8];
  std::snprintf(vid, sizeof vid, "%04x", gen1::kVendorId);
  std::snprintf(pid, sizeof pid, "%04x", gen1::kProductId);
  int rules = 0;
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] == '#') continue;
    ++rules;
    EXPECT_NE(line.find(std::string("idVendor}==\"") + vid + "\""), std::string::npos) << line;
    EXPECT_NE(line.find(std::string("idProduct}==\"") + pid + "\""), std::string::npos) << line;
    EXPECT_NE(line.find(std::string("product}==\"") + gen1::kProductName + "\""), std::string::npos) << line;
    EXPECT_NE(line.find("TAG+=\"uaccess\""), std::string::npos) << line;
  }
  EXPECT_EQ(rules, 2) << "one rule for the usb device node, one for hidraw";
}

}  // namespace
}  // namespace ht::devices
