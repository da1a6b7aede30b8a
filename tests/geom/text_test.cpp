// The message helpers of vdg/geom/text.h: quoting user text, numbers, extension tests.
#include "vdg/geom/text.h"

#include <gtest/gtest.h>

#include <limits>
#include <string>

namespace vdg {
namespace {

TEST(Text, QuotedTextIsOneLineAndCut) {
  EXPECT_EQ(quotedText("spot.obj"), "'spot.obj'");
  EXPECT_EQ(quotedText(std::string("a\nb\0c", 5)), "'a\\nb\\0c'");
  EXPECT_EQ(quotedText(std::string(kShownBytes, 'x')), "'" + std::string(kShownBytes, 'x') + "'");
  EXPECT_EQ(quotedText(std::string(kShownBytes + 1, 'x')), "'" + std::string(kShownBytes, 'x') + "...'");
  EXPECT_EQ(quotedText("abcdef", 3), "'abc...'");
  EXPECT_EQ(shownText("abcdef", 3), "abc...");
}

TEST(Text, NumbersAsPrintfGWritesThem) {
  EXPECT_EQ(numberText(0.5), "0.5");
  EXPECT_EQ(numberText(12.0), "12");
  EXPECT_EQ(numberText(1e12), "1e+12");
  EXPECT_EQ(numberText(1.0 / 3.0), "0.333333");
  EXPECT_EQ(numberText(1.0 / 3.0, 10), "0.3333333333");
  EXPECT_EQ(numberText(0.1, 17), "0.10000000000000001");
  EXPECT_EQ(numberText(std::numeric_limits<double>::infinity()), "inf");
  EXPECT_EQ(numberText(-std::numeric_limits<double>::infinity()), "-inf");
  EXPECT_EQ(numberText(std::numeric_limits<double>::quiet_NaN()), "nan");
}

TEST(Text, ExtensionsInAnyLetterCase) {
  EXPECT_TRUE(hasExtension("a/spot.obj", ".obj"));
  EXPECT_TRUE(hasExtension("SPOT.OBJ", ".obj"));
  EXPECT_FALSE(hasExtension("spot.objx", ".obj"));
  EXPECT_FALSE(hasExtension("obj", ".obj"));
  EXPECT_TRUE(hasGltfExtension("m.glTF"));
  EXPECT_TRUE(hasGltfExtension("m.GLB"));
  EXPECT_FALSE(hasGltfExtension("m.gltf.json"));
}

}  // namespace
}  // namespace vdg
