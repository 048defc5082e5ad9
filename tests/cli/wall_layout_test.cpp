// wall_layout_test.cpp - the live wall's layout file (cli/wall_layout.h): what a rank shows and where, and the
// refusals that name the file, the field and the value; the default split and wall option errors.
#include "cli/wall_layout.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "cli/cli_app.h"
#include "common/error.h"

namespace ht::cli {
namespace {

using ::testing::HasSubstr;

std::string refusal(const std::string& text, std::uint32_t views = 8, std::uint32_t ranks = 2) {
  try {
    parseWallLayout(text, "wall.json", views, ranks);
  } catch (const UsageError& e) { return e.what(); }
  return "accepted";
}

TEST(WallLayout, ParsesListsRangesColumnsMonitorsGeometriesAndDisplays) {
  const WallLayout layout = parseWallLayout(
      R"({"ranks": [{"projectors": [4, 0, 1], "monitor": "WALL-0", "columns": 2, "x_display": ":1"},
                    {"projectors": {"first": 5, "count": 3}, "geometry": "96x24+96+0"}]})",
      "wall.json", 8, 2);
  ASSERT_EQ(layout.ranks.size(), 2u);
  EXPECT_EQ(layout.ranks[0].projectors, (std::vector<std::uint32_t>{4, 0, 1}));
  EXPECT_EQ(layout.ranks[0].columns, 2u);
  EXPECT_EQ(layout.ranks[0].rows(), 2u);
  EXPECT_EQ(layout.ranks[0].monitor, "WALL-0");
  EXPECT_EQ(layout.ranks[0].xDisplay, ":1");
  EXPECT_EQ(layout.ranks[1].projectors, (std::vector<std::uint32_t>{5, 6, 7}));
  EXPECT_EQ(layout.ranks[1].columns, 3u) << "default: one row";
  EXPECT_EQ(layout.ranks[1].geometry, (present::Rect{96, 0, 96, 24}));
  EXPECT_EQ(layout.source, "wall.json");
}

TEST(WallLayout, RefusesWhatIsWrongNamingFileFieldAndValue) {
  EXPECT_THAT(refusal(R"({"ranks": [{"projectors": [0]}]})"),
              HasSubstr("layout wall.json: 'ranks' has 1 entries but the job has 2 rank(s)"));
  EXPECT_THAT(refusal(R"({"ranks": [{"projectors": [0]}, {"projectors": [8]}]})"),
              HasSubstr("'ranks[1].projectors[0]' = 8: expected a projector index 0-7"));
  EXPECT_THAT(refusal(R"({"ranks": [{"projectors": [0, 1]}, {"projectors": [1]}]})"),
              HasSubstr("'ranks[1].projectors' names projector 1 a second time"));
  EXPECT_THAT(refusal(R"({"ranks": [{"projectors": [0], "columns": 2}, {"projectors": [1]}]})"),
              HasSubstr("'ranks[0].columns' = 2: expected 1-1"));
  EXPECT_THAT(refusal(R"({"ranks": [{"projectors": [0]}, {"projectors": {"first": 6, "count": 3}}]})"),
              HasSubstr("'ranks[1].projectors.count' = 3"));
  EXPECT_THAT(
      refusal(R"({"ranks": [{"projectors": [0], "monitor": "A", "geometry": "1x1+0+0"}, {"projectors": [1]}]})"),
      HasSubstr("'ranks[0]' gives both 'monitor' and 'geometry'"));
  EXPECT_THAT(refusal(R"({"ranks": [{"projectors": [0], "geometry": "wide"}, {"projectors": [1]}]})"),
              HasSubstr("'ranks[0].geometry' = \"wide\""));
  EXPECT_THAT(refusal(R"({"ranks": [{"projectors": []}, {"projectors": [1]}]})"),
              HasSubstr("'ranks[0].projectors' is empty"));
  EXPECT_THAT(refusal(R"({"rank": []})"), HasSubstr("'ranks' is missing"));
  EXPECT_THAT(refusal("{not json"), HasSubstr("is not valid JSON"));
}

TEST(WallLayout, TheDefaultSplitsTheViewsIntoContiguousNearEqualGroups) {
  const WallLayout layout = defaultWallLayout(70, 4);
  ASSERT_EQ(layout.ranks.size(), 4u);
  EXPECT_EQ(layout.ranks[0].projectors.size(), 18u);
  EXPECT_EQ(layout.ranks[1].projectors.size(), 18u);
  EXPECT_EQ(layout.ranks[2].projectors.size(), 17u);
  EXPECT_EQ(layout.ranks[3].projectors.front(), 53u);
  EXPECT_EQ(layout.ranks[3].projectors.back(), 69u);
  EXPECT_EQ(layout.ranks[3].columns, 17u);
  EXPECT_THROW(defaultWallLayout(2, 3), UsageError);
}

TEST(WallCommand, OptionErrorsNameTheOption) {
  std::ostringstream out, err;
  const std::vector<std::string> both = {"wall", "--frames", "3", "--seconds", "2"};
  EXPECT_EQ(runCli(both, out, err), kExitUsage);
  EXPECT_THAT(err.str(), HasSubstr("give '--frames' or '--seconds', not both"));
  err.str("");
  const std::vector<std::string> delay = {"wall", "--debug-rank-delay", "1:x"};
  EXPECT_EQ(runCli(delay, out, err), kExitUsage);
  EXPECT_THAT(err.str(), HasSubstr("option '--debug-rank-delay' = '1:x': expected RANK:FRAME:MS"));
  const std::vector<std::string> help = {"wall", "--help"};
  EXPECT_EQ(runCli(help, out, err), kExitOk);
  EXPECT_THAT(out.str(), HasSubstr("swap barrier"));
}

}  // namespace
}  // namespace ht::cli
