#include "vdg/io/json_text.h"

#include <gtest/gtest.h>

namespace vdg {
namespace {

TEST(JsonText, ScalarArraysGoOnOneLine) {
  EXPECT_EQ(compactScalarArrays("{\n  \"view\": [\n    0.0,\n    0.15,\n    -1.0\n  ]\n}"),
            "{\n  \"view\": [0.0, 0.15, -1.0]\n}");
  EXPECT_EQ(compactScalarArrays("[\n  true,\n  null\n]"), "[true, null]");
  EXPECT_EQ(compactScalarArrays("[]"), "[]");
  EXPECT_EQ(compactScalarArrays("[\n]"), "[]");
}

TEST(JsonText, NestedArraysKeepTheirOuterLayout) {
  EXPECT_EQ(compactScalarArrays("[\n  [\n    1,\n    2\n  ],\n  [\n    3\n  ]\n]"), "[\n  [1, 2],\n  [3]\n]");
  EXPECT_EQ(compactScalarArrays("[\n  {\n    \"a\": 1\n  }\n]"), "[\n  {\n    \"a\": 1\n  }\n]");
}

TEST(JsonText, StringsAreNeverTouched) {
  const std::string text = "{\n  \"name\": \"ears [\\\"big\\\", 1]\",\n  \"v\": [\n    1\n  ]\n}";
  EXPECT_EQ(compactScalarArrays(text), "{\n  \"name\": \"ears [\\\"big\\\", 1]\",\n  \"v\": [1]\n}");
  EXPECT_EQ(compactScalarArrays("[\n  \"a\",\n  \"b\"\n]"), "[\n  \"a\",\n  \"b\"\n]");
}

}  // namespace
}  // namespace vdg
