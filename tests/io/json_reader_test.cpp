// The JSON layer every format reads through: nesting limit, one-line messages, no dumped values.
#include "json_reader.h"

#include <gtest/gtest.h>

#include <sys/stat.h>

#include <functional>

#include "support/error_of.h"
#include "support/test_meshes.h"
#include "vdg/io/read_file.h"

namespace vdg::io {
namespace {

using testing::errorOf;

std::string nested(int levels) { return std::string(levels, '[') + std::string(levels, ']'); }

TEST(JsonReader, NestingUpToTheLimitParses) { EXPECT_NO_THROW(parseJson(nested(kMaxJsonDepth), "doc.json")); }

TEST(JsonReader, DeepNestingIsRefusedWithoutRecursion) {
  // 65,000 levels crashed every reader before the limit (a recursive dump in the message).
  const std::string msg = errorOf([] { parseJson("{\"version\": " + nested(65'000) + "}", "deep.json"); });
  EXPECT_EQ(msg, "deep.json: JSON nested deeper than 64 levels (at line 1, column 76)");
}

// An array of many objects parses in one pass: nlohmann's callback parser, used before for the
// nesting limit, scanned the whole enclosing array after every object (O(n^2): 200,000 objects
// took minutes). No time is asserted; the count of elements read is the property, the test
// harness's watchdog the safety net.
TEST(JsonReader, AnArrayOfManyObjectsParsesInOnePass) {
  constexpr std::size_t kObjects = 200000;
  std::string text = "[";
  for (std::size_t i = 0; i < kObjects; ++i) text += i ? ", {\"a\": [1, 2]}" : "{\"a\": [1, 2]}";
  text += "]";
  const Json doc = parseJson(text, "doc.json");
  ASSERT_EQ(doc.size(), kObjects);
  EXPECT_EQ(doc.back().at("a").size(), 2u);
  // The limit still holds inside such an array.
  EXPECT_EQ(errorOf([&] {
              (void)parseJson("[{}, " + nested(kMaxJsonDepth) + "]", "doc.json");
            }).rfind("doc.json: JSON nested deeper than 64 levels", 0),
            0u);
}

TEST(JsonReader, SyntaxErrorsNameLineAndColumn) {
  const std::string msg = errorOf([] { parseJson("{\n  \"a\": 1,\n  \"b\": x\n}", "doc.json"); });
  EXPECT_EQ(msg.rfind("doc.json: not valid JSON at line 3, column 8", 0), 0u) << msg;
  EXPECT_EQ(msg.find('\n'), std::string::npos);
}

TEST(JsonReader, HugeNumbersAreAClearError) {
  const std::string msg = errorOf([] { parseJson("{\"a\": 1e999}", "doc.json"); });
  EXPECT_EQ(msg, "doc.json: not valid JSON: number overflow parsing '1e999'");
}

TEST(JsonReader, ValuesAreDescribedNotDumped) {
  EXPECT_EQ(describe(Json::parse("[1, [2, [3]]]")), "an array of 2 items");
  EXPECT_EQ(describe(Json::parse("{\"a\": {\"b\": 1}}")), "an object");
  EXPECT_EQ(describe(Json::parse("3")), "the number 3");
  EXPECT_EQ(describe(Json(std::string(1000, 'x'))), "the string \"" + std::string(40, 'x') + "...\"");
}

TEST(JsonReader, IntegersDoNotWrap) {
  const Ctx ctx{"m.json", ""};
  EXPECT_EQ(errorOf([&] { integer(Json::parse("4294967297"), ctx.key("version"), 1, 2); }),
            "m.json: 'version': expected an integer from 1 to 2, got 4294967297");
  EXPECT_EQ(errorOf([&] { integer(Json::parse("18446744073709551615"), ctx.key("n"), 0, 10); }),
            "m.json: 'n': expected an integer from 0 to 10, got 18446744073709551615");
  EXPECT_EQ(errorOf([&] { integer(Json::parse("1"), ctx.key("n"), 2, 10); }),
            "m.json: 'n': expected an integer from 2 to 10, got 1");
  EXPECT_EQ(integer(Json::parse("-3"), ctx.key("n"), -5, 10), -3);
  EXPECT_EQ(errorOf([&] { integer(Json::parse("1.5"), ctx.key("n"), 0, 10); }),
            "m.json: 'n': expected an integer from 0 to 10, got the number 1.5");
}

TEST(JsonReader, FormatVersionIsCheckedExactly) {
  const Ctx ctx{"m.json", ""};
  EXPECT_EQ(formatVersion(Json::parse(R"({"version": 1})"), ctx, "models", 1, 1), 1);
  EXPECT_EQ(errorOf([&] { formatVersion(Json::parse(R"({"version": 4294967297})"), ctx, "models", 1, 1); }),
            "m.json: 'version': this vdg reads models version 1, got 4294967297");
  EXPECT_EQ(errorOf([&] { formatVersion(Json::parse(R"({})"), ctx, "models", 1, 1); }),
            "m.json: missing 'version' (this vdg reads models version 1)");
  EXPECT_EQ(formatVersion(Json::parse(R"({})"), ctx, "cameras", 1, 1, /*missing=*/1), 1);
}

TEST(JsonReader, UnknownKeysAreNamedAndCut) {
  const Ctx ctx{"m.json", ""};
  const std::string msg = errorOf([&] {
    allowKeys(Json::parse("{\"" + std::string(100, 'k') + "\": 1}"), ctx, {"a", "b"});
  });
  EXPECT_EQ(msg, "m.json: unknown key '" + std::string(40, 'k') + "...' (expected one of 'a', 'b')");
}

TEST(ReadFile, RefusesWhatIsNotARegularFile) {
  testing::TempDir dir;
  EXPECT_EQ(errorOf([&] { readFileLimited(dir.path().string(), "model", 100); }),
            dir.path().string() + ": is a folder, not a model file");
  EXPECT_EQ(errorOf([&] { readFileLimited("/dev/zero", "model", 100); }),
            "/dev/zero: is a character device, not a model file");
  EXPECT_EQ(errorOf([&] { readFileLimited(dir.file("none.json"), "model", 100); }),
            dir.file("none.json") + ": no such file (model)");
}

TEST(ReadFile, RefusesAFifoWithoutHanging) {
  testing::TempDir dir;
  const std::string fifo = dir.file("pipe.json");
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  EXPECT_EQ(errorOf([&] { readFileLimited(fifo, "model", 100); }), fifo + ": is a FIFO (named pipe), not a model file");
}

TEST(ReadFile, RefusesFilesOverTheLimit) {
  testing::TempDir dir;
  testing::writeText(dir.file("big.json"), std::string(2000, ' '));
  EXPECT_EQ(errorOf([&] { readFileLimited(dir.file("big.json"), "model", 1000); }),
            dir.file("big.json") + ": model file is 2000 bytes, more than the limit of 1000 bytes");
  EXPECT_EQ(readFileLimited(dir.file("big.json"), "model", 2000).size(), 2000u);
}

}  // namespace
}  // namespace vdg::io
