// arguments_test.cpp - the hand-written option parser: values, flags, and every usage error.
#include "cli/arguments.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <array>
#include <string>
#include <vector>

#include "common/error.h"

namespace ht::cli {
namespace {

using ::testing::HasSubstr;

const std::array<OptionSpec, 4> kSpecs = {{
    {"--spp", "", "N", "samples"},
    {"--output", "-o", "FILE", "output"},
    {"--validation", "", "", "flag"},
    {"--name", "", "TEXT", "text"},
}};

ParsedArguments parse(std::vector<std::string> args) { return parseArguments("holotrace test", kSpecs, args); }

std::string usageErrorOf(std::vector<std::string> args) {
  try {
    parse(args).unsignedValue("--spp", 1, 64);
  } catch (const UsageError& e) { return e.what(); }
  return "(no UsageError)";
}

TEST(CliArguments, ParsesValuesFlagsAliasesAndEqualsForm) {
  const auto parsed = parse({"--spp", "8", "-o", "a.png", "--validation", "--name=x=y"});
  EXPECT_EQ(parsed.unsignedValue("--spp", 1, 64), 8u);
  EXPECT_EQ(parsed.text("--output"), "a.png");
  EXPECT_TRUE(parsed.has("--validation"));
  EXPECT_EQ(parsed.text("--name"), "x=y");
  EXPECT_FALSE(parsed.has("--missing"));
  EXPECT_EQ(parsed.textOr("--missing", "fallback"), "fallback");
}

TEST(CliArguments, AbsentNumericOptionIsEmpty) { EXPECT_FALSE(parse({}).unsignedValue("--spp", 1, 64).has_value()); }

TEST(CliArguments, UnknownOptionNamesItAndPointsToHelp) {
  EXPECT_EQ(usageErrorOf({"--spq", "4"}), "holotrace test: unknown option '--spq' (see holotrace test --help)");
  EXPECT_THAT(usageErrorOf({"--spq=4"}), HasSubstr("unknown option '--spq'"));
}

TEST(CliArguments, MissingValueIsAnError) {
  EXPECT_THAT(usageErrorOf({"--spp"}), HasSubstr("option '--spp' needs a value"));
  EXPECT_THAT(usageErrorOf({"-o", "--validation"}), HasSubstr("option '--output' needs a value"));
  EXPECT_THAT(usageErrorOf({"--name="}), HasSubstr("empty value"));
}

TEST(CliArguments, InvalidNumbersNameOptionValueAndRange) {
  EXPECT_EQ(usageErrorOf({"--spp", "abc"}),
            "holotrace test: option '--spp' = 'abc': expected an integer in [1, 64] (see holotrace test --help)");
  EXPECT_THAT(usageErrorOf({"--spp", "0"}), HasSubstr("'0': expected an integer in [1, 64]"));
  EXPECT_THAT(usageErrorOf({"--spp", "65"}), HasSubstr("'65'"));
  EXPECT_THAT(usageErrorOf({"--spp", "4x"}), HasSubstr("'4x'"));
  EXPECT_THAT(usageErrorOf({"--spp", "99999999999999999999999"}), HasSubstr("expected an integer"));
  EXPECT_THAT(usageErrorOf({"--spp=-3"}), HasSubstr("'-3'"));
}

TEST(CliArguments, DecimalNumbersAreCheckedLikeIntegers) {
  EXPECT_DOUBLE_EQ(*parse({"--name", "0.08"}).numberValue("--name", 0.0, 1.0), 0.08);
  EXPECT_DOUBLE_EQ(*parse({"--name=1"}).numberValue("--name", 0.0, 1.0), 1.0);
  EXPECT_FALSE(parse({}).numberValue("--name", 0.0, 1.0).has_value());
  auto errorOf = [](std::vector<std::string> args) {
    try {
      parse(args).numberValue("--name", 0.0, 1.0);
    } catch (const UsageError& e) { return std::string(e.what()); }
    return std::string("(no UsageError)");
  };
  EXPECT_EQ(errorOf({"--name", "1.5"}),
            "holotrace test: option '--name' = '1.5': expected a number in [0, 1] (see holotrace test --help)");
  for (const char* bad : {"nan", "inf", "0.1x", "0x1p-3", "1e400"}) {
    EXPECT_THAT(errorOf({"--name", bad}), HasSubstr("expected a number in [0, 1]")) << bad;
  }
  EXPECT_THAT(errorOf({"--name=-0.1"}), HasSubstr("'-0.1': expected a number in [0, 1]"));
}

TEST(CliArguments, RepeatedPositionalAndValuedFlagsAreErrors) {
  EXPECT_THAT(usageErrorOf({"--spp", "1", "--spp", "2"}), HasSubstr("given twice"));
  EXPECT_THAT(usageErrorOf({"stray"}), HasSubstr("unexpected argument 'stray'"));
  EXPECT_THAT(usageErrorOf({"--validation=1"}), HasSubstr("takes no value"));
}

TEST(CliArguments, HelpDetectionAndFormatting) {
  const std::vector<std::string> withHelp = {"--spp", "2", "-h"};
  EXPECT_TRUE(wantsHelp(withHelp));
  EXPECT_FALSE(wantsHelp(std::vector<std::string>{"--spp", "2"}));
  const std::string help = formatOptions(kSpecs);
  EXPECT_THAT(help, HasSubstr("-o, --output FILE"));
  EXPECT_THAT(help, HasSubstr("-h, --help"));
  EXPECT_THAT(help, HasSubstr("--validation"));
}

}  // namespace
}  // namespace ht::cli
