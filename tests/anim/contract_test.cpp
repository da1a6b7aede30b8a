// The per-frame contract (curve.h): every invalid input to every anim evaluation entry point
// returns false and leaves the output untouched (filled with a sentinel first, compared after);
// the by-value convenience forms throw vdg::Error instead.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "anim_fixtures.h"
#include "vdg/anim/ease.h"
#include "vdg/geom/error.h"

namespace vdg::anim {
namespace {

constexpr double kSentinel = -12345.5;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();
const double kBadTimes[] = {kNaN, kInf, -kInf};

std::vector<double> sentinelBuffer(std::size_t size) { return std::vector<double>(size, kSentinel); }

void expectUntouched(const std::vector<double>& buffer) {
  for (std::size_t i = 0; i < buffer.size(); ++i) ASSERT_EQ(buffer[i], kSentinel) << "element " << i << " was written";
}

// Sizes other than `dim`: empty, one short, one long, far too long.
std::vector<std::size_t> badSizes(int dim) {
  const auto d = static_cast<std::size_t>(dim);
  std::vector<std::size_t> sizes = {0, d + 1, 2 * d + 3};
  if (d > 1) sizes.push_back(d - 1);
  return sizes;
}

// Runs `job(t, out)` with every bad size (at a good time) and every bad time (at the good size).
template <typename Job>
void expectRefusals(int dim, Job job, const std::string& what) {
  for (std::size_t size : badSizes(dim)) {
    std::vector<double> out = sentinelBuffer(size);
    EXPECT_FALSE(job(0.5, std::span<double>(out))) << what << ": size " << size;
    expectUntouched(out);
  }
  for (double t : kBadTimes) {
    std::vector<double> out = sentinelBuffer(static_cast<std::size_t>(dim));
    EXPECT_FALSE(job(t, std::span<double>(out))) << what << ": t " << t;
    expectUntouched(out);
  }
  // The same job with good input writes every entry (so the refusals above are not vacuous).
  std::vector<double> out = sentinelBuffer(static_cast<std::size_t>(dim));
  EXPECT_TRUE(job(0.5, std::span<double>(out))) << what;
  for (double v : out) EXPECT_NE(v, kSentinel) << what;
}

TEST(AnimContract, CurveEvaluateAndDerivative) {
  for (CurveKind kind : {CurveKind::kLinear, CurveKind::kCatmullRom, CurveKind::kNaturalCubic, CurveKind::kBezier}) {
    const Curve c = fixtures::curve3(kind);
    expectRefusals(
        c.dimension(), [&](double t, std::span<double> out) { return c.evaluate(t, out); },
        std::string("evaluate ") + curveKindName(kind));
    expectRefusals(
        c.dimension(), [&](double t, std::span<double> out) { return c.derivative(t, out); },
        std::string("derivative ") + curveKindName(kind));
  }
}

TEST(AnimContract, ArcLengthEvaluation) {
  for (ArcLengthMethod method : {ArcLengthMethod::kTable, ArcLengthMethod::kAdaptive}) {
    ArcLengthOptions options;
    options.method = method;
    const ArcLengthCurve a = ArcLengthCurve::build(fixtures::curve3(), options);
    expectRefusals(
        3, [&](double s, std::span<double> out) { return a.evaluateAtDistance(s, out); },
        std::string("evaluateAtDistance ") + arcLengthMethodName(method));
    expectRefusals(
        3, [&](double f, std::span<double> out) { return a.evaluateAtFraction(f, out); },
        std::string("evaluateAtFraction ") + arcLengthMethodName(method));
  }
}

TEST(AnimContract, TrackEvaluate) {
  for (const Track& track : fixtures::tracks()) {
    expectRefusals(
        track.dimension(), [&](double t, std::span<double> out) { return track.evaluate(t, out); },
        "track " + track.name());
  }
}

TEST(AnimContract, QuaternionCurveEvaluate) {
  const QuaternionCurve c = fixtures::quaternionCurve();
  for (double t : kBadTimes) {
    Quaternion q(kSentinel, kSentinel, kSentinel, kSentinel);
    EXPECT_FALSE(c.evaluate(t, q)) << t;
    EXPECT_EQ(q.coeffs(), Eigen::Vector4d::Constant(kSentinel)) << t;
  }
  Quaternion q(kSentinel, kSentinel, kSentinel, kSentinel);
  EXPECT_TRUE(c.evaluate(1.5, q));
  EXPECT_NEAR(q.norm(), 1.0, 1e-12);
}

TEST(AnimContract, CameraPathEvaluate) {
  for (const CameraPath& path : fixtures::cameraPaths()) {
    for (double t : kBadTimes) {
      Camera c;
      c.eye = c.target = c.up = Eigen::Vector3d::Constant(kSentinel);
      c.fov_deg = c.ortho_height = kSentinel;
      EXPECT_FALSE(path.evaluate(t, c)) << t;
      EXPECT_EQ(c.eye, Eigen::Vector3d::Constant(kSentinel));
      EXPECT_EQ(c.target, Eigen::Vector3d::Constant(kSentinel));
      EXPECT_EQ(c.up, Eigen::Vector3d::Constant(kSentinel));
      EXPECT_EQ(c.fov_deg, kSentinel);
      EXPECT_EQ(c.ortho_height, kSentinel);
    }
    Camera c;
    EXPECT_TRUE(path.evaluate(1.0, c));
  }
}

template <typename F>
void expectError(F&& f, const std::string& fragment) {
  try {
    f();
    ADD_FAILURE() << "no vdg::Error, expected one containing '" << fragment << "'";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
  }
}

TEST(AnimContract, ConvenienceFormsThrowNamingTheProblem) {
  const Curve c = fixtures::curve3();
  expectError([&] { (void)c.at(kNaN); }, "curve: time nan is not finite");
  expectError([&] { (void)c.derivativeAt(kInf); }, "curve: time inf is not finite");
  expectError([&] { (void)c.segmentControls(c.segmentCount()); },
              "curve: segment 4 out of range (the curve has 4 segments)");
  expectError([&] { (void)c.segmentControls(-1); }, "curve: segment -1 out of range");
  const std::vector<Track> tracks = fixtures::tracks();
  expectError([&] { (void)tracks[0].at(kNaN); }, "track 'scalar': time nan is not finite");
  expectError([&] { (void)tracks[0].scalarAt(-kInf); }, "track 'scalar': time -inf is not finite");
  expectError([&] { (void)tracks[4].rotationAt(kNaN); }, "track 'slerp': time nan is not finite");
  expectError([&] { (void)tracks[0].rotationAt(0.5); }, "track 'scalar': rotationAt on a scalar track");
  expectError([&] { (void)fixtures::quaternionCurve().at(kNaN); }, "quaternion curve: time nan is not finite");
  const std::vector<CameraPath> paths = fixtures::cameraPaths();
  expectError([&] { (void)paths[0].eyeAt(kNaN); }, "camera path: time nan is not finite");
  expectError([&] { (void)paths[0].cameraAt(kInf); }, "camera path: time inf is not finite");
}

// Ease functions reject nothing (curve.h, ease.h): every number, NaN included, maps into [0, 1].
TEST(AnimContract, EaseIsTotal) {
  constexpr double kEaseEndTol = 1e-12;  // ease(1) of the piecewise kinds is 1 up to rounding
  for (const Ease& e : {Ease::linear(), Ease::sine(), Ease::sinusoidal(0.2, 0.7), Ease::parabolic(0.3, 0.6)}) {
    EXPECT_EQ(e.evaluate(kNaN), 0.0) << e.describe();
    EXPECT_EQ(e.evaluate(-kInf), 0.0) << e.describe();
    EXPECT_NEAR(e.evaluate(kInf), 1.0, kEaseEndTol) << e.describe();
  }
}

}  // namespace
}  // namespace vdg::anim
