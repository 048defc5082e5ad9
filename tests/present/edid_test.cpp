// edid_test.cpp - EDID base block: monitor name and serial descriptors, header/checksum/length faults.
#include <gtest/gtest.h>

#include "present/edid.h"

namespace ht::present {
namespace {

TEST(Edid, SyntheticBlockCarriesTheMonitorName) {
  auto edid = makeEdid("LKG-P00671");
  ASSERT_EQ(edid.size(), 128u);
  EdidInfo info = parseEdid(edid);
  EXPECT_EQ(info.monitorName, "LKG-P00671");
  EXPECT_EQ(info.serialText, "");
}

TEST(Edid, ThirteenCharacterNameHasNoTerminator) {
  EXPECT_EQ(parseEdid(makeEdid("LKG01Do12HjQE")).monitorName, "LKG01Do12HjQE");
  EXPECT_THROW(makeEdid("LKG01Do12HjQE1"), PresentError);
}

TEST(Edid, SerialDescriptorAndTrailingSpaces) {
  auto edid = makeEdid("Toshiba");
  // Descriptor 3 (offset 90) -> serial text "ABC  " padded with spaces, checksum fixed up.
  edid[90 + 3] = 0xFF;
  const char* serial = "ABC  \n       ";
  for (int i = 0; i < 13; ++i) edid[90 + 5 + i] = static_cast<std::uint8_t>(serial[i]);
  unsigned sum = 0;
  for (int i = 0; i < 127; ++i) sum += edid[i];
  edid[127] = static_cast<std::uint8_t>((256 - sum % 256) % 256);
  EdidInfo info = parseEdid(edid);
  EXPECT_EQ(info.monitorName, "Toshiba");
  EXPECT_EQ(info.serialText, "ABC");
}

TEST(Edid, FaultsAreNamed) {
  auto edid = makeEdid("LKG-P");
  try {
    parseEdid(std::span(edid).first(100));
    FAIL();
  } catch (const PresentError& e) { EXPECT_NE(std::string(e.what()).find("100 bytes"), std::string::npos) << e.what(); }
  auto badHeader = edid;
  badHeader[1] = 0x12;
  EXPECT_THROW(parseEdid(badHeader), PresentError);
  auto badSum = edid;
  badSum[127] ^= 1;
  try {
    parseEdid(badSum);
    FAIL();
  } catch (const PresentError& e) { EXPECT_NE(std::string(e.what()).find("checksum"), std::string::npos) << e.what(); }
}

TEST(Edid, ExtensionBlocksAfterTheBaseBlockAreIgnored) {
  auto edid = makeEdid("LKG-2K");
  edid.resize(256, 0x5A);
  EXPECT_EQ(parseEdid(edid).monitorName, "LKG-2K");
}

}  // namespace
}  // namespace ht::present
