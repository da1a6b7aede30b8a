// Deformation from feature lines (vdg/deform/feature_lines.h, the "lines" edit op) and the shared
// line-pairs file (vdg/io/line_pairs.h): Beier and Neely 92's warp moves a translated line's
// vertices by the translation in the image plane at their own depth, leaves far vertices and
// identical pairs bit for bit alone, replays from the edit log, and every bad file is one line.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "test_meshes.h"
#include "vdg/deform/edits.h"
#include "vdg/deform/feature_lines.h"
#include "vdg/deform/key_edit.h"
#include "vdg/geom/error.h"
#include "vdg/io/edit_script.h"
#include "vdg/io/line_pairs.h"

namespace vdg {
namespace {

constexpr int kSide = 200;  // image width and height, pixels
// Pixel error of one float rounding of a coordinate of magnitude <= 1 seen at 100 pixels per unit
// (2^-24 * 100 = 6e-6), with room for the two coordinates: the issue's 1e-5 pixels.
constexpr double kPixelTolerance = 1e-5;
// A perspective view's depth is the float vertex's: relative 2^-23 of the ~5 unit distance.
constexpr double kDepthTolerance = 5 * 1.2e-7;

// A parallel camera looking down -Z at the origin, 2 units high: 100 pixels per unit, and the grid
// point (x, y) at pixel (100 + 100 x, 100 - 100 y) exactly.
Camera orthoCamera() {
  Camera c;
  c.eye = {0, 0, 5};
  c.ortho_height = 2.0;
  c.fov_deg = 0;
  return c;
}
Camera perspectiveCamera() {
  Camera c;
  c.eye = {0.3, 0.2, 5};
  c.target = {0, 0, 0};
  c.fov_deg = 25;
  return c;
}

Eigen::Vector3d vertex(const std::vector<float>& p, std::size_t v) { return {p[3 * v], p[3 * v + 1], p[3 * v + 2]}; }

// The pair that translates the line through the projections of grid vertices a and b by `offset`.
FeatureLinePair translatedLine(const Camera& camera, const TriMesh& mesh, std::size_t a, std::size_t b,
                               const Eigen::Vector2d& offset) {
  const Eigen::Vector2d p = project(camera, kSide, kSide, vertex(mesh.positions, a)).pixel;
  const Eigen::Vector2d q = project(camera, kSide, kSide, vertex(mesh.positions, b)).pixel;
  return {p, q, p + offset, q + offset};
}

std::vector<float> warped(const Camera& camera, const TriMesh& mesh, const LinesOp& op) {
  std::vector<float> positions = mesh.positions;
  const std::vector<EditOp> ops{op};
  applyEdits(camera, mesh.triangles, positions, ops, std::array<int, 2>{kSide, kSide}, "test");
  return positions;
}

// Checks that the vertices first..last of grid row `row` (n x n grid; those between the line's
// ends, where Beier-Neely's distance is 0) moved by `offset` pixels keeping their depth.
void expectRowMoved(const Camera& camera, const TriMesh& mesh, const std::vector<float>& after, int n, int row,
                    int first, int last, const Eigen::Vector2d& offset, double tolerance) {
  for (int i = first; i <= last; ++i) {
    const std::size_t v = static_cast<std::size_t>(row * n + i);
    const Projected before = project(camera, kSide, kSide, vertex(mesh.positions, v));
    const Projected now = project(camera, kSide, kSide, vertex(after, v));
    EXPECT_NEAR(now.pixel.x() - before.pixel.x(), offset.x(), tolerance) << "vertex " << v;
    EXPECT_NEAR(now.pixel.y() - before.pixel.y(), offset.y(), tolerance) << "vertex " << v;
    EXPECT_NEAR(now.depth, before.depth, kDepthTolerance) << "vertex " << v;
  }
}

TEST(FeatureLines, TranslatedLineMovesItsVerticesByTheOffsetAtTheirDepth) {
  const int n = 17;
  const TriMesh mesh = test::grid(n, 0.125);  // x, y in [-1, 1], exact in float
  const Camera camera = orthoCamera();
  const Eigen::Vector2d offset(7.5, -3.25);
  const int row = 12;  // y = 0.5
  LinesOp op;
  op.pairs = {translatedLine(camera, mesh, row * n + 2, row * n + 14, offset)};
  const std::vector<float> after = warped(camera, mesh, op);
  expectRowMoved(camera, mesh, after, n, row, 2, 14, offset, kPixelTolerance);
  // Beyond an end the distance to the end counts: the row's outer vertices move less.
  const std::size_t outer = static_cast<std::size_t>(row * n);
  const double outer_motion = (project(camera, kSide, kSide, vertex(after, outer)).pixel -
                               project(camera, kSide, kSide, vertex(mesh.positions, outer)).pixel)
                                  .norm();
  EXPECT_LT(outer_motion, 0.9 * offset.norm());
  EXPECT_GT(outer_motion, 0.1 * offset.norm());
}

TEST(FeatureLines, PerspectiveLineMovesByTheOffsetRelatively) {
  const int n = 9;
  const TriMesh mesh = test::grid(n, 0.25);
  const Camera camera = perspectiveCamera();
  const Eigen::Vector2d offset(-6.0, 4.5);
  LinesOp op;
  op.pairs = {translatedLine(camera, mesh, 4 * n + 1, 4 * n + 7, offset)};
  const std::vector<float> after = warped(camera, mesh, op);
  // Relative to the motion: float positions at ~100 pixels per unit again.
  expectRowMoved(camera, mesh, after, n, 4, 1, 7, offset, 1e-5 * offset.norm() + kPixelTolerance);
}

TEST(FeatureLines, VerticesBeyondTheFalloffStayPutBitForBit) {
  const int n = 17;
  const TriMesh mesh = test::grid(n, 0.125);
  const Camera camera = orthoCamera();
  LinesOp op;
  op.pairs = {translatedLine(camera, mesh, 8 * n + 6, 8 * n + 10, {5, 5})};  // y = 0, x in [-0.25, 0.25]
  op.settings.falloff_px = 30;
  const std::vector<float> after = warped(camera, mesh, op);
  std::size_t near_moved = 0, far = 0;
  for (std::size_t v = 0; v < after.size() / 3; ++v) {
    const Eigen::Vector2d pixel = project(camera, kSide, kSide, vertex(mesh.positions, v)).pixel;
    // Beier-Neely's distance to the segment from (75, 100) to (125, 100).
    const double dx = std::max({75.0 - pixel.x(), 0.0, pixel.x() - 125.0});
    const double dist = std::hypot(dx, pixel.y() - 100.0);
    const bool moved = vertex(after, v) != vertex(mesh.positions, v);
    if (dist >= op.settings.falloff_px) {
      ++far;
      EXPECT_FALSE(moved) << "vertex " << v << " at " << dist << " px";
    } else {
      near_moved += moved ? 1 : 0;
    }
  }
  EXPECT_GT(far, 200u);
  EXPECT_GT(near_moved, 10u);
}

TEST(FeatureLines, MotionFadesWithDistanceAndBackFacesMoveAsTheFront) {
  const std::vector<FeatureLinePair> pairs{{{0, 0}, {10, 0}, {0, 4}, {10, 4}}};
  const FeatureLineSettings settings;
  EXPECT_NEAR(featureLineMotion({5, 0}, pairs, settings).y(), 4.0, 1e-12);
  const double half = featureLineMotion({5, 32}, pairs, settings).y();  // (1 - 32/64)^2 = 1/4
  EXPECT_NEAR(half, 1.0, 1e-12);
  EXPECT_EQ(featureLineMotion({5, 64}, pairs, settings), Eigen::Vector2d::Zero());
  // A point behind the grid at the same pixel (a back face) moves by the same pixels.
  const Camera camera = orthoCamera();
  std::vector<float> positions{0.25f, 0.5f, 0.0f, 0.25f, 0.5f, -1.0f};
  const std::vector<FeatureLinePair> line{{{100, 50}, {150, 50}, {110, 50}, {160, 50}}};
  warpByFeatureLines(camera, kSide, kSide, positions, line, settings);
  EXPECT_FLOAT_EQ(positions[0], positions[3]);
  EXPECT_FLOAT_EQ(positions[1], positions[4]);
  EXPECT_EQ(positions[5], -1.0f);
}

TEST(FeatureLines, IdenticalPairsChangeNothingBitForBit) {
  const TriMesh mesh = test::grid(9, 0.25);
  for (const Camera& camera : {orthoCamera(), perspectiveCamera()}) {
    LinesOp op;
    op.pairs = {translatedLine(camera, mesh, 10, 16, {0, 0}), {{3, 7}, {150, 180}, {3, 7}, {150, 180}}};
    EXPECT_EQ(warped(camera, mesh, op), mesh.positions);
  }
}

TEST(FeatureLines, TheKeyReplaysFromItsEditLogAndTheOpRoundTrips) {
  RawViewDependentModel m;
  m.base = test::grid(9, 0.25);
  m.base_path = "base.obj";
  m.keys.push_back({"front", "front.obj", m.base, Eigen::Vector3d(0, 0, 1), std::nullopt, std::nullopt, {}, {}});
  m.resolveViews();
  m.validate();
  EditLog log = startEditLog(m, m.keys[0], "front.origin.obj");
  LinesOp op;
  op.pairs = {{{60, 90}, {140, 90}, {64, 80}, {136, 96}}, {{100, 40}, {100, 160}, {95, 40}, {110, 165}}};
  op.settings = {0.5, 1.5, 0.25, 80};
  const std::vector<EditOp> ops{op};
  const auto reports = deformKey(m, 0, log, ops, std::array<int, 2>{kSide, kSide}, "lines");
  ASSERT_EQ(reports.size(), 1u);
  EXPECT_GT(reports[0].moved, 20u);
  EXPECT_EQ(replayEditLog(m.base, log, "log"), m.keys[0].mesh.positions);
  const EditLog read = parseEditLog(formatEditLog(log), "k.edits.json");
  EXPECT_EQ(replayEditLog(m.base, read, "k.edits.json"), m.keys[0].mesh.positions);
  const EditOp back = parseEditOp(editOpToJson(op), "op");
  ASSERT_EQ(editKind(back), EditKind::kLines);
  EXPECT_EQ(std::get<LinesOp>(back).pairs, op.pairs);
  EXPECT_EQ(std::get<LinesOp>(back).settings, op.settings);
}

TEST(FeatureLines, SnappingPutsTheModelSideOnTheSilhouette) {
  const TriMesh sphere = test::sphere(24, 48, 0.8);
  const Camera camera = orthoCamera();  // the sphere's outline: a circle of 80 pixels about (100, 100)
  const auto silhouette = projectedSilhouette(camera, kSide, kSide, sphere.positions, sphere.triangles);
  ASSERT_GT(silhouette.size(), 40u);
  const std::vector<FeatureLinePair> pairs{{{100, 5}, {190, 100}, {100, 10}, {185, 100}}};
  const auto snapped = snapToSilhouette(pairs, silhouette);
  // Within the polygon's sag of the circle (r (1 - cos(pi / 48)) = 0.17 pixels) of radius 80.
  for (const Eigen::Vector2d& end : {snapped[0].model_p, snapped[0].model_q})
    EXPECT_NEAR((end - Eigen::Vector2d(100, 100)).norm(), 80.0, 0.2);
  EXPECT_NEAR(snapped[0].model_p.x(), 100.0, 0.2);
  EXPECT_EQ(snapped[0].drawing_p, pairs[0].drawing_p);
}

std::string errorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(FeatureLines, BadPairsFilesGiveOneLineNamingTheFile) {
  const std::pair<const char*, const char*> cases[] = {
      {"{", "not valid JSON"},
      {R"({"version": 1})", "missing key 'lines'"},
      {R"({"version": 1, "lines": []})", "'lines': expected a non-empty array"},
      {R"({"version": 2, "lines": []})", "'version'"},
      {R"({"version": 1, "a": 0, "lines": [{"src": [[0,0],[1,0]], "dst": [[0,0],[1,0]]}]})", "'a': expected"},
      {R"({"version": 1, "lines": [{"src": [[0,0],[1,0]]}]})", "'lines'[0]: missing key 'dst'"},
      {R"({"version": 1, "lines": [{"src": [[0,0]], "dst": [[0,0],[1,0]]}]})", "'lines'[0].'src': expected 2"},
      {R"({"version": 1, "lines": [{"src": [[0,0],[1,"x"]], "dst": [[0,0],[1,0]]}]})", "'lines'[0].'src'[1][1]"},
      {R"({"version": 1, "lines": [{"src": [[0,0],[1,0]], "dst": [[0,0],[1,0]], "w": 1}]})", "'w'"},
  };
  for (const auto& [text, expected] : cases) {
    const std::string message = errorOf([&] { parseLinePairs(text, "PAIRS.json"); });
    EXPECT_EQ(message.rfind("PAIRS.json: ", 0), 0u) << message;
    EXPECT_NE(message.find(expected), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
  // The op's own checks: a line of no length, a falloff out of range.
  const std::string zero = errorOf([] {
    parseEditScript(R"({"ops": [{"op": "lines", "lines": [{"src": [[5,5],[5,5]], "dst": [[0,0],[1,0]]}]}]})", "E.json");
  });
  EXPECT_EQ(zero,
            "E.json: 'ops'[0] (lines).'lines'[0].'src': the line has no length (its two ends are the same pixel)");
  const std::string falloff = errorOf([] {
    parseEditScript(
        R"({"ops": [{"op": "lines", "falloff_px": -1, "lines": [{"src": [[5,5],[6,5]], "dst": [[0,0],[1,0]]}]}]})",
        "E.json");
  });
  EXPECT_EQ(falloff, "E.json: 'ops'[0] (lines).'falloff_px': must be > 0 and finite, got -1");
  // More pairs than the warp's cost allows (#V x pairs).
  const std::vector<FeatureLinePair> many(kMaxFeatureLinePairs + 1, FeatureLinePair{{0, 0}, {1, 0}, {0, 1}, {1, 1}});
  const auto too_many = checkFeatureLines(many, {});
  ASSERT_TRUE(too_many);
  EXPECT_EQ(too_many->field, "'lines'");
  EXPECT_FALSE(checkFeatureLines(std::span(many).first(kMaxFeatureLinePairs), {}));
  // Without the image size the op cannot place its pixels.
  const TriMesh mesh = test::grid(3, 1);
  std::vector<float> positions = mesh.positions;
  const std::vector<EditOp> ops{LinesOp{{{{0, 0}, {1, 0}, {0, 1}, {1, 1}}}, {}}};
  EXPECT_NE(errorOf([&] { applyEdits(orthoCamera(), mesh.triangles, positions, ops); }).find("image_size"),
            std::string::npos);
}

TEST(FeatureLines, MorphLinesFilesReadTheSameShape) {
  const LinePairsFile file = parseLinePairs(
      R"({"version": 1, "a": 2, "b": 1, "p": 0, "lines": [{"src": [[0,0],[10,0]], "dst": [[1,1],[11,2]]}]})", "L");
  ASSERT_EQ(file.pairs.size(), 1u);
  EXPECT_EQ(file.pairs[0].dst_q, Eigen::Vector2d(11, 2));
  EXPECT_EQ(file.a, 2.0);
  EXPECT_EQ(file.b, 1.0);
  EXPECT_EQ(file.p, 0.0);
}

}  // namespace
}  // namespace vdg
