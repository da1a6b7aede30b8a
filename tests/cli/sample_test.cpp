// vdg sample as a user runs it: ease specs sampled to a table, CSV and SVG, checked against the
// ease formula of Parent 4.2 (sine ease: ease(t) = (sin(t*pi - pi/2) + 1) / 2); bad specs exit 1,
// bad options exit 2, each with one line naming the file or option.
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <cmath>
#include <cstdlib>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "support/test_meshes.h"

namespace {

struct Result {
  int code;
  std::string out;
  std::string err;
};

// Runs `vdg ARGS` in `dir` through the shell, capturing stdout and stderr separately.
Result runIn(const vdg::testing::TempDir& dir, const std::string& args) {
  const std::string out = dir.file(".stdout"), err = dir.file(".stderr");
  const std::string cmd =
      "cd '" + dir.path().string() + "' && '" VDG_BINARY "' " + args + " >'" + out + "' 2>'" + err + "'";
  const int status = std::system(cmd.c_str());
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, vdg::testing::readText(out), vdg::testing::readText(err)};
}

// Parent 4.2, sine ease-in/ease-out.
double sineEase(double t) { return (std::sin(t * std::numbers::pi - std::numbers::pi / 2) + 1) / 2; }

constexpr double kPrintTol = 1e-9;  // sample prints 10 significant digits

std::vector<std::vector<double>> parseCsvRows(const std::string& text, std::string& header) {
  std::istringstream lines(text);
  std::getline(lines, header);
  std::vector<std::vector<double>> rows;
  for (std::string line; std::getline(lines, line);) {
    std::vector<double> row;
    std::istringstream cells(line);
    for (std::string cell; std::getline(cells, cell, ',');) row.push_back(std::stod(cell));
    rows.push_back(row);
  }
  return rows;
}

int lineCount(const std::string& s) { return static_cast<int>(std::count(s.begin(), s.end(), '\n')); }

TEST(Sample, SineEaseCsvMatchesParentsFormula) {
  vdg::testing::TempDir dir;
  vdg::testing::writeText(dir.file("ease.json"), R"({"ease": "sine"})");
  const Result r = runIn(dir, "sample ease.json --at 0,0.25,0.5,0.75,1 --csv");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.err, "");
  std::string header;
  const auto rows = parseCsvRows(r.out, header);
  EXPECT_EQ(header, "t,value");
  ASSERT_EQ(rows.size(), 5u);
  for (const auto& row : rows) {
    ASSERT_EQ(row.size(), 2u);
    EXPECT_NEAR(row[1], sineEase(row[0]), kPrintTol) << "t = " << row[0];
  }
  EXPECT_NEAR(rows[1][1], 0.1464466094, kPrintTol) << "Parent's ease(0.25)";
  EXPECT_EQ(rows[0][1], 0.0);
  EXPECT_EQ(rows[4][1], 1.0);
}

TEST(Sample, EvenSamplesCoverTheRangeInATable) {
  vdg::testing::TempDir dir;
  vdg::testing::writeText(dir.file("ease.json"), R"({"ease": "sine"})");
  const Result r = runIn(dir, "sample ease.json --samples 9");
  ASSERT_EQ(r.code, 0) << r.err;
  std::istringstream lines(r.out);
  std::string header;
  std::getline(lines, header);
  EXPECT_EQ(header, "t\tvalue");
  int i = 0;
  double previous = -1.0;
  for (double t = 0, v = 0; lines >> t >> v; ++i) {
    EXPECT_NEAR(t, i / 8.0, kPrintTol);
    EXPECT_NEAR(v, sineEase(t), kPrintTol);
    EXPECT_GT(v, previous) << "an ease curve increases";
    previous = v;
  }
  EXPECT_EQ(i, 9);
}

TEST(Sample, EaseVariantsStartAtZeroAndEndAtOne) {
  vdg::testing::TempDir dir;
  for (const char* spec : {R"({"ease": "linear"})", R"({"ease": "sinusoidal", "t1": 0.2, "t2": 0.7})",
                           R"({"ease": "parabolic", "a": 0.3, "b": 0.6})"}) {
    vdg::testing::writeText(dir.file("e.json"), spec);
    const Result r = runIn(dir, "sample e.json --at 0,1 --csv");
    ASSERT_EQ(r.code, 0) << spec << ": " << r.err;
    std::string header;
    const auto rows = parseCsvRows(r.out, header);
    ASSERT_EQ(rows.size(), 2u) << spec;
    EXPECT_NEAR(rows[0][1], 0.0, kPrintTol) << spec;
    EXPECT_NEAR(rows[1][1], 1.0, kPrintTol) << spec;
  }
}

TEST(Sample, LinearCurveAtHalfTimeIsTheMidpoint) {
  vdg::testing::TempDir dir;
  vdg::testing::writeText(dir.file("c.json"), R"({"curve": "linear", "points": [[0, 0, 0], [2, 4, -6]]})");
  const Result r = runIn(dir, "sample c.json --at 0.5 --csv");
  ASSERT_EQ(r.code, 0) << r.err;
  std::string header;
  const auto rows = parseCsvRows(r.out, header);
  EXPECT_EQ(header, "t,x,y,z");
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_NEAR(rows[0][1], 1.0, kPrintTol);
  EXPECT_NEAR(rows[0][2], 2.0, kPrintTol);
  EXPECT_NEAR(rows[0][3], -3.0, kPrintTol);
}

TEST(Sample, SvgPlotIsWrittenAndItsTitleIsEscaped) {
  vdg::testing::TempDir dir;
  vdg::testing::writeText(dir.file("a<b&c.json"), R"({"ease": "sine"})");
  const Result r = runIn(dir, "sample 'a<b&c.json' --samples 20 -o plot.svg");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.out, "");
  const std::string svg = vdg::testing::readText(dir.file("plot.svg"));
  EXPECT_EQ(svg.rfind("<svg ", 0), 0u) << svg.substr(0, 80);
  EXPECT_NE(svg.find("<polyline"), std::string::npos);
  EXPECT_NE(svg.find(">a&lt;b&amp;c.json</text>"), std::string::npos) << "the file name is text, not markup";
  EXPECT_EQ(svg.find("a<b"), std::string::npos);
}

TEST(Sample, BadSpecsAreInputErrorsNamingTheFile) {
  vdg::testing::TempDir dir;
  vdg::testing::writeText(dir.file("bogus.json"), R"({"ease": "bogus"})");
  vdg::testing::writeText(dir.file("two.json"), R"({"ease": "sine", "curve": "linear"})");
  vdg::testing::writeText(dir.file("bad.json"), R"({"ease": )");
  vdg::testing::writeText(dir.file("range.json"), R"({"ease": "sinusoidal", "t1": 0.9, "t2": 0.1})");
  for (const char* file : {"bogus.json", "two.json", "bad.json", "range.json", "missing.json", "."}) {
    const Result r = runIn(dir, std::string("sample '") + file + "' --samples 3");
    EXPECT_EQ(r.code, 1) << file << ": " << r.err;
    EXPECT_EQ(lineCount(r.err), 1) << r.err;
    EXPECT_EQ(r.err.rfind(std::string("vdg: error: ") + file + ":", 0), 0u) << r.err;
    EXPECT_EQ(r.out, "") << file;
  }
}

TEST(Sample, BadOptionsAreUsageErrorsNamingTheOption) {
  vdg::testing::TempDir dir;
  vdg::testing::writeText(dir.file("ease.json"), R"({"ease": "sine"})");
  const std::pair<const char*, const char*> cases[] = {{"--samples 0", "--samples"},
                                                       {"--samples nan", "--samples"},
                                                       {"--samples 2.5", "--samples"},
                                                       {"--at 0.5,nan", "--at"},
                                                       {"--at ''", "--at"},
                                                       {"--at 1e999", "--at"},
                                                       {"", "--samples"},
                                                       {"--at 0.5 --samples 3", "--at"},
                                                       {"--samples 3 --csv -o p.svg", "--csv"}};
  for (const auto& [args, option] : cases) {
    const Result r = runIn(dir, std::string("sample ease.json ") + args);
    EXPECT_EQ(r.code, 2) << args << ": " << r.err;
    EXPECT_EQ(lineCount(r.err), 1) << r.err;
    EXPECT_EQ(r.err.rfind("vdg: sample: ", 0), 0u) << r.err;
    EXPECT_NE(r.err.find(option), std::string::npos) << args << ": " << r.err;
  }
  EXPECT_FALSE(std::filesystem::exists(dir.file("p.svg")));
}

}  // namespace
