// json_fields_test.cpp - the shared JSON readers of camera_models (json_fields.h): N-vectors, "auto", image sizes
// and the one image-size limit. Every error names the file, the dotted field and the offending value.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <string>

#include "camera_models/json_fields.h"
#include "camera_test_support.h"
#include "common/error.h"
#include "common/image_limits.h"

namespace ht::test {
namespace {

using nlohmann::json;
using ::testing::HasSubstr;

const detail::JsonLocation kAt{"fields.json", "section"};

TEST(JsonFields, VectorReadsExactlyNFiniteNumbers) {
  const json object = json::parse(R"({"p": [1, -2.5, 3e2], "q": [0.5, 4]})");
  EXPECT_EQ(detail::requireVector<3>(kAt, object, "p", "expected [x, y, z]"), glm::dvec3(1.0, -2.5, 300.0));
  EXPECT_EQ(detail::requireVector<2>(kAt, object, "q", "expected [x, y]"), glm::dvec2(0.5, 4.0));
  EXPECT_FALSE(detail::optionalVector<2>(kAt, object, "missing", "expected [x, y]").has_value());
}

TEST(JsonFields, VectorErrorsNameFileFieldAndValue) {
  for (const char* bad :
       {R"({"p": [1, 2]})", R"({"p": [1, 2, 3, 4]})", R"({"p": [1, "2", 3]})", R"({"p": 7})", R"({"p": "auto"})"}) {
    const json object = json::parse(bad);
    ConfigError e = catchConfigError([&] { detail::requireVector<3>(kAt, object, "p", "expected [x, y, z]"); });
    EXPECT_EQ(e.file(), "fields.json") << bad;
    EXPECT_EQ(e.field(), "section.p") << bad;
    EXPECT_EQ(e.value(), object["p"].dump()) << bad;
    EXPECT_EQ(e.expected(), "expected [x, y, z]") << bad;
  }
  ConfigError missing = catchConfigError([] { detail::requireVector<2>(kAt, json::object(), "q", "expected [x, y]"); });
  EXPECT_EQ(missing.field(), "section.q");
  EXPECT_EQ(missing.value(), "(missing)");
}

TEST(JsonFields, AutoOnlyWhereAllowed) {
  const json object = json::parse(R"({"p": "auto", "n": "automatic"})");
  EXPECT_TRUE(detail::isAuto(object["p"]));
  EXPECT_FALSE(detail::isAuto(object["n"]));
  EXPECT_FALSE(detail::optionalVector<3>(kAt, object, "p", "expected [x, y, z] or \"auto\"", true).has_value());
  EXPECT_THROW(detail::optionalVector<3>(kAt, object, "p", "expected [x, y, z]"), ConfigError);
}

TEST(JsonFields, ImageSizeUpToTheOneLimit) {
  const std::string largest = std::to_string(kMaxImageSide);
  const json ok = json::parse(R"({"image": {"width": )" + largest + R"(, "height": 1}})");
  const detail::ImageSize size = detail::requireImageSize(kAt, ok, "image");
  EXPECT_EQ(size.width, kMaxImageSide);
  EXPECT_EQ(size.height, 1u);

  const json tooWide =
      json::parse(R"({"image": {"width": )" + std::to_string(kMaxImageSide + 1) + R"(, "height": 1}})");
  ConfigError e = catchConfigError([&] { detail::requireImageSize(kAt, tooWide, "image"); });
  EXPECT_EQ(e.field(), "section.image.width");
  EXPECT_EQ(e.value(), std::to_string(kMaxImageSide + 1));
  EXPECT_THAT(e.expected(), HasSubstr(largest));

  const json typo = json::parse(R"({"image": {"width": 4, "hieght": 4}})");
  EXPECT_EQ(catchConfigError([&] { detail::requireImageSize(kAt, typo, "image"); }).field(), "section.image.hieght");
  const json notObject = json::parse(R"({"image": [4, 4]})");
  ConfigError shape = catchConfigError([&] { detail::requireImageSize(kAt, notObject, "image"); });
  EXPECT_EQ(shape.field(), "section.image");
  EXPECT_EQ(shape.value(), "[4,4]");
  EXPECT_FALSE(detail::optionalImageSize(kAt, json::object(), "image").has_value());
  EXPECT_EQ(catchConfigError([&] { detail::requireImageSize(kAt, json::object(), "image"); }).value(), "(missing)");
}

TEST(JsonFields, ImageSideRejectsZeroAndFractions) {
  for (const char* bad : {R"({"w": 0})", R"({"w": 12.5})", R"({"w": -3})"}) {
    const json object = json::parse(bad);
    ConfigError e = catchConfigError([&] { detail::requireImageSide(kAt, object, "w"); });
    EXPECT_EQ(e.field(), "section.w") << bad;
    EXPECT_EQ(e.value(), object["w"].dump()) << bad;
  }
  EXPECT_EQ(detail::requireImageSide(kAt, json::parse(R"({"w": {"value": 64}})"), "w", true), 64u);
}

}  // namespace
}  // namespace ht::test
