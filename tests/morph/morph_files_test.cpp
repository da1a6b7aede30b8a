// The grid, lines and key-drawings files of `vdg morph` (vdg/io/morph_files.h): round trips through
// the writers, and every refusal as its whole one-line message.
#include "vdg/io/morph_files.h"

#include <gtest/gtest.h>

#include <string>

#include "support/error_of.h"
#include "support/test_meshes.h"

namespace vdg {
namespace {

using testing::errorOf;

// A 2 x 3 grid over a 40 x 20 image, and the same grid with its middle column bent.
constexpr const char* kSrcPoints = "[[0, 0], [20, 0], [40, 0], [0, 20], [20, 20], [40, 20]]";
constexpr const char* kDstPoints = "[[0, 0], [25, 0], [40, 0], [0, 20], [15, 20], [40, 20]]";

std::string stillGrid(const std::string& src = kSrcPoints, const std::string& dst = kDstPoints) {
  return std::string(R"({"version": 1, "rows": 2, "cols": 3, "src": )") + src + R"(, "dst": )" + dst + "}";
}

std::string gridError(const std::string& text) {
  return errorOf([&] { (void)parseMorphGrid(text, "grid.json"); });
}
std::string linesError(const std::string& text) {
  return errorOf([&] { (void)parseMorphLines(text, "lines.json"); });
}
std::string drawingsError(const std::string& text) {
  return errorOf([&] { (void)parseKeyDrawings(text, "keys.json"); });
}

TEST(MorphGridFile, StillGridReadsRowMajorPoints) {
  const MorphGridFile f = parseMorphGrid(stillGrid(), "grid.json");
  EXPECT_EQ(f.rows, 2);
  EXPECT_EQ(f.cols, 3);
  EXPECT_FALSE(f.keyed);
  ASSERT_EQ(f.src.size(), 1u);
  EXPECT_EQ(f.src[0].grid.at(1, 2), Eigen::Vector2d(40, 20));
  EXPECT_EQ(f.dst[0].grid.at(0, 1), Eigen::Vector2d(25, 0));
  EXPECT_EQ(f.dst[0].grid.at(1, 1), Eigen::Vector2d(15, 20));
  // A still grid is the same at every frame.
  EXPECT_EQ(f.srcAt(7.5).points, f.src[0].grid.points);
  EXPECT_EQ(f.dstAt(0).points, f.dst[0].grid.points);
}

TEST(MorphGridFile, StillAndKeyedRoundTrip) {
  const MorphGridFile still = parseMorphGrid(stillGrid(), "grid.json");
  EXPECT_EQ(parseMorphGrid(formatMorphGrid(still), "again"), still);
  const std::string keyed = std::string(R"({"version": 1, "rows": 2, "cols": 3, "keys": [)") +
                            R"({"frame": 0, "src": )" + kSrcPoints + R"(, "dst": )" + kDstPoints + "}, " +
                            R"({"frame": 12.5, "src": )" + kDstPoints + R"(, "dst": )" + kSrcPoints + "}]}";
  const MorphGridFile f = parseMorphGrid(keyed, "grid.json");
  EXPECT_TRUE(f.keyed);
  ASSERT_EQ(f.src.size(), 2u);
  EXPECT_EQ(f.src[1].time, 12.5);
  EXPECT_EQ(f.dst[1].time, 12.5);
  EXPECT_EQ(parseMorphGrid(formatMorphGrid(f), "again"), f);
  // Written and read back through a file.
  const testing::TempDir dir;
  writeMorphGrid(dir.file("g.json"), f);
  EXPECT_EQ(readMorphGrid(dir.file("g.json")), f);
}

TEST(MorphGridFile, NumbersRoundTripExactly) {
  MorphGridFile f = parseMorphGrid(stillGrid(), "grid.json");
  f.src[0].grid.at(0, 1) = {0.1 + 0.2, 1.0 / 3.0};
  EXPECT_EQ(parseMorphGrid(formatMorphGrid(f), "again"), f);
}

TEST(MorphGridFile, RefusesBadStructureNamingFileAndKey) {
  EXPECT_EQ(gridError("[1]"), "grid.json: expected a JSON object at the top level, got an array of 1 item");
  EXPECT_EQ(gridError(R"({"rows": 2})"), "grid.json: missing 'version' (this vdg reads morph grid files version 1)");
  EXPECT_EQ(gridError(R"({"version": 2, "rows": 2})"),
            "grid.json: 'version': this vdg reads morph grid files version 1, got 2");
  EXPECT_EQ(gridError(R"({"version": 1, "rows": 2, "cols": 3, "src": [], "dst": [], "size": 1})"),
            "grid.json: unknown key 'size' (expected one of 'version', 'rows', 'cols', 'src', 'dst', 'keys')");
  EXPECT_EQ(gridError(R"({"version": 1, "cols": 3})"), "grid.json: missing key 'rows'");
  EXPECT_EQ(gridError(R"({"version": 1, "rows": 1, "cols": 3})"),
            "grid.json: 'rows': expected an integer from 2 to 1024, got 1");
  EXPECT_EQ(gridError(R"({"version": 1, "rows": 2, "cols": 2.5})"),
            "grid.json: 'cols': expected an integer from 2 to 1024, got the number 2.5");
  EXPECT_EQ(gridError(R"({"version": 1, "rows": 2, "cols": 3})"), "grid.json: missing key 'src' and 'dst' (or 'keys')");
  EXPECT_EQ(gridError(std::string(R"({"version": 1, "rows": 2, "cols": 3, "src": )") + kSrcPoints + "}"),
            "grid.json: missing key 'dst'");
  EXPECT_EQ(gridError(stillGrid(kSrcPoints, "[[0, 0], [25, 0], [40, 0], [0, 20], [15, 20]]")),
            "grid.json: 'dst': expected 6 [x, y] points, got 5");
  EXPECT_EQ(gridError(stillGrid(kSrcPoints, "{}")),
            "grid.json: 'dst': expected an array of [x, y] points, got an object");
  EXPECT_EQ(gridError(stillGrid(kSrcPoints, "[[0, 0], [25, 0], [40, 0], [0, \"x\"], [15, 20], [40, 20]]")),
            "grid.json: 'dst'[3][1]: expected a number, got the string \"x\"");
  EXPECT_EQ(gridError(stillGrid(kSrcPoints, "[[0, 0], [25, 0], [40, 0], [0, 20, 1], [15, 20], [40, 20]]")),
            "grid.json: 'dst'[3]: expected a point [x, y], got an array of 3 items");
  EXPECT_EQ(gridError(stillGrid(kSrcPoints, "[[0, 0], [25, 0], [40, 0], [0, 1e300], [15, 20], [40, 20]]")),
            "grid.json: 'dst'[3][1]: expected a coordinate within +-10000000 pixels, got the number 1e+300");
  EXPECT_EQ(gridError(std::string(R"({"version": 1, "rows": 2, "cols": 3, "src": )") + kSrcPoints + R"(, "dst": )" +
                      kDstPoints + R"(, "keys": []})"),
            "grid.json: give either 'src' and 'dst' (a still grid) or 'keys' (grids at key frames), not both");
  EXPECT_EQ(
      gridError(R"({"version": 1, "rows": 2, "cols": 3, "keys": []})"),
      "grid.json: 'keys': expected a non-empty array of {\"frame\", \"src\", \"dst\"} keys, got an array of 0 items");
}

TEST(MorphGridFile, RefusesKeyFramesOutOfOrder) {
  const std::string key = std::string(R"("src": )") + kSrcPoints + R"(, "dst": )" + kDstPoints;
  EXPECT_EQ(gridError(R"({"version": 1, "rows": 2, "cols": 3, "keys": [{"frame": 3, )" + key + R"(}, {"frame": 3, )" +
                      key + "}]}"),
            "grid.json: 'keys'[1].'frame': expected a frame after the previous key's (3), got 3");
  EXPECT_EQ(gridError(R"({"version": 1, "rows": 2, "cols": 3, "keys": [{"frame": -1, )" + key + "}]}"),
            "grid.json: 'keys'[0].'frame': expected a number from 0 to 1000000, got -1");
  EXPECT_EQ(gridError(R"({"version": 1, "rows": 2, "cols": 3, "keys": [{)" + key + "}]}"),
            "grid.json: 'keys'[0]: missing key 'frame'");
}

// Crossing grid lines are the morph library's check (morph::validateGrid), reported under the file
// and key: the message starts with them and stays on one line.
TEST(MorphGridFile, RefusesCrossingGridLinesNamingTheKey) {
  const std::string crossed = "[[0, 0], [20, 0], [40, 0], [0, 20], [45, 20], [40, 20]]";  // row 1: x 45 then 40
  const std::string e = gridError(stillGrid(kSrcPoints, crossed));
  EXPECT_EQ(e.rfind("grid.json: 'dst': ", 0), 0u) << e;
  EXPECT_EQ(e.find('\n'), std::string::npos) << e;
  const std::string up = "[[0, 0], [20, 30], [40, 0], [0, 20], [20, 20], [40, 20]]";  // column 1: y 30 then 20
  const std::string e2 = gridError(stillGrid(up, kDstPoints));
  EXPECT_EQ(e2.rfind("grid.json: 'src': ", 0), 0u) << e2;
}

// ---- lines ---------------------------------------------------------------------------------------

constexpr const char* kLines =
    R"({"version": 1, "a": 0.5, "b": 1.5, "p": 0.25, "lines": [
         {"src": [[10, 10], [30, 10]], "dst": [[12, 8], [28, 14]]},
         {"src": [[5, 30], [5, 50]], "dst": [[6, 30], [8, 52]]}]})";

TEST(MorphLinesFile, ReadsPairsAndParametersAndRoundTrips) {
  const MorphLinesFile f = parseMorphLines(kLines, "lines.json");
  ASSERT_EQ(f.src.size(), 2u);
  EXPECT_EQ(f.src[0].p, Eigen::Vector2d(10, 10));
  EXPECT_EQ(f.src[0].q, Eigen::Vector2d(30, 10));
  EXPECT_EQ(f.dst[1].q, Eigen::Vector2d(8, 52));
  EXPECT_EQ(f.params.a, 0.5);
  EXPECT_EQ(f.params.b, 1.5);
  EXPECT_EQ(f.params.p, 0.25);
  EXPECT_EQ(parseMorphLines(formatMorphLines(f), "again"), f);
  const testing::TempDir dir;
  writeMorphLines(dir.file("l.json"), f);
  EXPECT_EQ(readMorphLines(dir.file("l.json")), f);
}

TEST(MorphLinesFile, ParametersDefaultToTheLibrarys) {
  const MorphLinesFile f =
      parseMorphLines(R"({"version": 1, "lines": [{"src": [[0, 0], [1, 0]], "dst": [[0, 0], [0, 1]]}]})", "lines.json");
  const morph::FeatureParams defaults;
  EXPECT_EQ(f.params.a, defaults.a);
  EXPECT_EQ(f.params.b, defaults.b);
  EXPECT_EQ(f.params.p, defaults.p);
}

TEST(MorphLinesFile, RefusesBadValuesNamingFileAndKey) {
  const std::string one = R"("lines": [{"src": [[0, 0], [1, 0]], "dst": [[0, 0], [0, 1]]}])";
  EXPECT_EQ(linesError(R"({"version": 1, "a": 0, )" + one + "}"),
            "lines.json: 'a': expected a number above 0 and at most 1000000, got 0");
  EXPECT_EQ(linesError(R"({"version": 1, "b": -1, )" + one + "}"),
            "lines.json: 'b': expected a number from 0 to 16, got -1");
  EXPECT_EQ(linesError(R"({"version": 1, "p": 2, )" + one + "}"),
            "lines.json: 'p': expected a number from 0 to 1, got 2");
  EXPECT_EQ(linesError(R"({"version": 1})"), "lines.json: missing key 'lines'");
  EXPECT_EQ(linesError(R"({"version": 1, "lines": {}})"),
            "lines.json: 'lines': expected a non-empty array of {\"src\", \"dst\"} line pairs, got an object");
  EXPECT_EQ(linesError(R"({"version": 1, "lines": [{"src": [[0, 0], [1, 0]]}]})"),
            "lines.json: 'lines'[0]: missing key 'dst'");
  EXPECT_EQ(linesError(R"({"version": 1, "lines": [{"src": [[0, 0]], "dst": [[0, 0], [0, 1]]}]})"),
            "lines.json: 'lines'[0].'src': expected 2 [x, y] points, got 1");
  EXPECT_EQ(linesError(R"({"version": 1, "lines": [{"src": [[0, 0], [1, 0]], "dst": [[0, 0], [0, 1]], "w": 1}]})"),
            "lines.json: 'lines'[0]: unknown key 'w' (expected one of 'src', 'dst')");
}

// A zero-length line is the morph library's check (morph::validateFeatureLines), under the file.
TEST(MorphLinesFile, RefusesZeroLengthLineNamingTheFile) {
  const std::string e = linesError(
      R"({"version": 1, "lines": [{"src": [[0, 0], [1, 0]], "dst": [[0, 0], [0, 1]]},
                                  {"src": [[4, 4], [4, 4]], "dst": [[0, 0], [0, 1]]}]})");
  EXPECT_EQ(e.rfind("lines.json: 'lines': ", 0), 0u) << e;
  EXPECT_NE(e.find('1'), std::string::npos) << e;  // names line 1
  EXPECT_EQ(e.find('\n'), std::string::npos) << e;
}

TEST(MorphLinesFile, RefusesAPairThatCollapsesInBetween) {
  // Source from left to right, destination from right to left: the inbetween at t = 0.5 is a point.
  EXPECT_EQ(linesError(R"({"version": 1, "lines": [{"src": [[0, 0], [1, 0]], "dst": [[0, 0], [0, 1]]},
                                                   {"src": [[10, 5], [20, 5]], "dst": [[20, 5], [10, 5]]}]})"),
            "lines.json: 'lines'[1]: the source and destination lines point in opposite directions, so the line "
            "collapses to a point at t = 0.5; give the destination's endpoints the other way round");
}

// ---- key drawings --------------------------------------------------------------------------------

constexpr const char* kDrawings =
    R"({"version": 1, "curve": "catmull-rom", "width": 64, "height": 48, "keys": [
         {"time": 0, "strokes": [[[0, 0], [10, 0], [20, 0]], [[5, 5], [5, 15]]]},
         {"time": 1, "strokes": [[[0, 10], [20, 10]], [[6, 5], [6, 10], [6, 15]]]},
         {"time": 3, "strokes": [[[0, 20], [20, 20]], [[7, 5], [7, 15]]]}]})";

TEST(KeyDrawingsFile, ReadsKeysAsGivenAndRoundTrips) {
  const KeyDrawingsFile f = parseKeyDrawings(kDrawings, "keys.json");
  EXPECT_EQ(f.curve, morph::InbetweenCurve::kCatmullRom);
  EXPECT_EQ(f.width, 64);
  EXPECT_EQ(f.height, 48);
  ASSERT_EQ(f.keys.size(), 3u);
  EXPECT_EQ(f.keys[2].time, 3.0);
  EXPECT_EQ(f.keys[0].strokes[0].size(), 3u);  // not resampled
  EXPECT_EQ(f.keys[1].strokes[0].size(), 2u);
  EXPECT_EQ(parseKeyDrawings(formatKeyDrawings(f), "again"), f);
  const testing::TempDir dir;
  writeKeyDrawings(dir.file("k.json"), f);
  EXPECT_EQ(readKeyDrawings(dir.file("k.json")), f);
}

TEST(KeyDrawingsFile, DefaultsAreLinearOn512) {
  const KeyDrawingsFile f =
      parseKeyDrawings(R"({"version": 1, "keys": [{"time": 0, "strokes": [[[0, 0], [1, 1]]]}]})", "keys.json");
  EXPECT_EQ(f.curve, morph::InbetweenCurve::kLinear);
  EXPECT_EQ(f.width, 512);
  EXPECT_EQ(f.height, 512);
}

TEST(KeyDrawingsFile, RefusesBadKeysNamingFileAndKey) {
  EXPECT_EQ(drawingsError(R"({"version": 1, "curve": "cubic", "keys": []})"),
            "keys.json: 'curve': unknown value 'cubic' (expected one of 'linear', 'catmull-rom')");
  EXPECT_EQ(drawingsError(R"({"version": 1, "width": 0, "keys": []})"),
            "keys.json: 'width': expected an integer from 1 to 16384, got 0");
  EXPECT_EQ(drawingsError(R"({"version": 1, "keys": []})"),
            "keys.json: 'keys': expected a non-empty array of {\"time\", \"strokes\"} keys, got an array of 0 items");
  EXPECT_EQ(
      drawingsError(R"({"version": 1, "keys": [{"time": 0, "strokes": []}]})"),
      "keys.json: 'keys'[0].'strokes': expected a non-empty array of strokes (each an array of [x, y] points), got "
      "an array of 0 items");
  EXPECT_EQ(drawingsError(R"({"version": 1, "keys": [{"time": 0, "strokes": [[[0, 0]]]}]})"),
            "keys.json: 'keys'[0].'strokes'[0]: expected at least 2 [x, y] points, got 1");
  EXPECT_EQ(drawingsError(R"({"version": 1, "keys": [{"time": 1, "strokes": [[[0, 0], [1, 1]]]},
                                                      {"time": 0.5, "strokes": [[[0, 0], [1, 1]]]}]})"),
            "keys.json: 'keys'[1].'time': expected a time after the previous key's (1), got 0.5");
  EXPECT_EQ(drawingsError(R"({"version": 1, "keys": [{"time": 0, "strokes": [[[0, 0], [1, 1]]]},
                                                      {"time": 1, "strokes": [[[0, 0], [1, 1]], [[2, 2], [3, 3]]]}]})"),
            "keys.json: 'keys'[1].'strokes': expected as many strokes as keys[0] has (1), got 2");
  EXPECT_EQ(drawingsError(R"({"version": 1, "keys": [{"strokes": [[[0, 0], [1, 1]]]}]})"),
            "keys.json: 'keys'[0]: missing key 'time'");
}

// The example's files (examples/morph2d) are valid, and the grids cover the 200 x 200 faces: their
// outer rows and columns lie on the image border.
TEST(MorphFilesExample, Morph2dFilesReadAndCoverTheImages) {
  const std::string dir = std::string(VDG_SOURCE_DIR) + "/examples/morph2d/";
  const MorphGridFile grid = readMorphGrid(dir + "grid.json");
  EXPECT_FALSE(grid.keyed);
  for (const morph::WarpGrid& g : {grid.src[0].grid, grid.dst[0].grid}) {
    for (int c = 0; c < g.cols; ++c) {
      EXPECT_EQ(g.at(0, c).y(), 0.0);
      EXPECT_EQ(g.at(g.rows - 1, c).y(), 200.0);
    }
    for (int r = 0; r < g.rows; ++r) {
      EXPECT_EQ(g.at(r, 0).x(), 0.0);
      EXPECT_EQ(g.at(r, g.cols - 1).x(), 200.0);
    }
  }
  EXPECT_EQ(readMorphLines(dir + "lines.json").src.size(), 7u);
  const KeyDrawingsFile drawings = readKeyDrawings(dir + "drawings.json");
  EXPECT_EQ(drawings.keys.size(), 3u);
  EXPECT_EQ(drawings.curve, morph::InbetweenCurve::kCatmullRom);
}

}  // namespace
}  // namespace vdg
