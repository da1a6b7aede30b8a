// Animated view-dependent models (Rademacher 99, section 4; vdg/viewdep/animated_model.h):
// key meshes are reproduced at their frame and view; offsets follow the natural (or periodic)
// cubic spline in time, checked against a spline solved here independently (all polynomial
// pieces' coefficients at once by dense Gaussian elimination, not the second-derivative form the
// implementation uses); world and skinned offsets on a rotating limb; the per-frame contract,
// allocation-free evaluation and the validation of bad raw models.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <span>
#include <string>
#include <vector>

#include "support/allocation_counter.h"
#include "support/error_of.h"
#include "support/test_meshes.h"
#include "vdg/viewdep/animated_model.h"

namespace vdg {
namespace {

using Eigen::Vector3d;
using testing::errorOf;

constexpr double kKeyTol = 1e-5;          // float rounding of base + (key - base)
constexpr double kSplineTol = 1e-9;       // double-precision cardinal coefficients against the direct solve
constexpr double kFloatSplineTol = 2e-5;  // evaluate() blends in float
constexpr double kSeamValueTol = 1e-12;
constexpr double kSeamSlopeTol = 1e-6;      // one-sided second-order differences, step kStep
constexpr double kSeamCurvatureTol = 1e-4;  // one-sided first-order differences, step kStep
constexpr double kStep = 1e-3;
constexpr int kFrames = 40;

// ---- An independent cubic spline: pieces p_k(s) = a + b s + c s^2 + d s^3, s = x - t_k --------
// All 4P coefficients solved at once from interpolation, C1 and C2 joins and the end conditions.
std::vector<double> solveDense(std::vector<std::vector<double>> a, std::vector<double> b) {
  const std::size_t n = b.size();
  for (std::size_t col = 0; col < n; ++col) {
    std::size_t pivot = col;
    for (std::size_t r = col + 1; r < n; ++r)
      if (std::abs(a[r][col]) > std::abs(a[pivot][col])) pivot = r;
    std::swap(a[col], a[pivot]);
    std::swap(b[col], b[pivot]);
    for (std::size_t r = col + 1; r < n; ++r) {
      const double f = a[r][col] / a[col][col];
      for (std::size_t c = col; c < n; ++c) a[r][c] -= f * a[col][c];
      b[r] -= f * b[col];
    }
  }
  std::vector<double> x(n);
  for (std::size_t r = n; r-- > 0;) {
    double s = b[r];
    for (std::size_t c = r + 1; c < n; ++c) s -= a[r][c] * x[c];
    x[r] = s / a[r][r];
  }
  return x;
}

struct DirectSpline {
  std::vector<double> knots;  // P + 1 knots (periodic: the last is the first + period)
  std::vector<double> coef;   // 4 per piece

  double operator()(double x) const {
    std::size_t k = 0;
    while (k + 2 < knots.size() && x >= knots[k + 1]) ++k;
    const double s = x - knots[k];
    return coef[4 * k] + s * (coef[4 * k + 1] + s * (coef[4 * k + 2] + s * coef[4 * k + 3]));
  }
};

// Natural (periodic = false) or periodic spline through (t_j, y_j); periodic closes with t_0 + N.
DirectSpline directSpline(const std::vector<int>& t, const std::vector<double>& y, bool periodic, int period) {
  DirectSpline s;
  for (int f : t) s.knots.push_back(f);
  std::vector<double> ys = y;
  if (periodic) {
    s.knots.push_back(t[0] + period);
    ys.push_back(y[0]);
  }
  const std::size_t pieces = s.knots.size() - 1, n = 4 * pieces;
  std::vector<std::vector<double>> a(n, std::vector<double>(n, 0.0));
  std::vector<double> b(n, 0.0);
  std::size_t row = 0;
  auto value = [&](std::size_t k, double sv, double rhs) {  // p_k(sv) = rhs
    for (int p = 0; p < 4; ++p) a[row][4 * k + p] = std::pow(sv, p);
    b[row++] = rhs;
  };
  for (std::size_t k = 0; k < pieces; ++k) {
    const double h = s.knots[k + 1] - s.knots[k];
    value(k, 0.0, ys[k]);
    value(k, h, ys[k + 1]);
  }
  // Joins: slope and curvature of piece k at its end = those of piece k+1 at its start.
  auto join = [&](std::size_t k, std::size_t next) {
    const double h = s.knots[k + 1] - s.knots[k];
    a[row][4 * k + 1] = 1;
    a[row][4 * k + 2] = 2 * h;
    a[row][4 * k + 3] = 3 * h * h;
    a[row][4 * next + 1] -= 1;
    ++row;
    a[row][4 * k + 2] = 2;
    a[row][4 * k + 3] = 6 * h;
    a[row][4 * next + 2] -= 2;
    ++row;
  };
  for (std::size_t k = 0; k + 1 < pieces; ++k) join(k, k + 1);
  if (periodic) {
    join(pieces - 1, 0);
  } else {
    a[row++][2] = 2;  // p_0''(0) = 0
    const double h = s.knots[pieces] - s.knots[pieces - 1];
    a[row][4 * (pieces - 1) + 2] = 2;  // p_last''(h) = 0
    a[row++][4 * (pieces - 1) + 3] = 6 * h;
  }
  s.coef = solveDense(a, b);
  return s;
}

// ---- Fixtures ----------------------------------------------------------------------------------
// A sphere whose base animation bobs and stretches over kFrames frames.
RawViewDependentModel animatedSphere(bool loop) {
  RawViewDependentModel raw;
  raw.source = "anim.vdg.json";
  raw.base = testing::uvSphere(4, 6);
  raw.base_animation = BaseAnimationSpec{};
  raw.base_animation->obj_sequence = "frame_%02d.obj";
  raw.base_animation->last = kFrames - 1;
  raw.base_animation->loop = loop;
  for (int f = 0; f < kFrames; ++f) {
    std::vector<float> p = raw.base.positions;
    const double phase = 2.0 * std::numbers::pi * f / kFrames;
    for (std::size_t v = 0; v < raw.base.vertexCount(); ++v) {
      p[3 * v] *= static_cast<float>(1.0 + 0.2 * std::sin(phase));
      p[3 * v + 1] += static_cast<float>(0.3 * std::cos(phase));
    }
    raw.base_frames.push_back(p);
  }
  raw.base.positions = raw.base_frames[0];
  return raw;
}

// A key at `frame` seen from `view`: the base at that frame with every vertex moved by a
// frame-dependent, vertex-dependent offset.
RawKey keyAt(const RawViewDependentModel& raw, const std::string& name, const Vector3d& view, int frame,
             double amount) {
  RawKey key;
  key.name = name;
  key.mesh = raw.base;
  key.mesh.positions = raw.base_frames[static_cast<std::size_t>(frame)];
  for (std::size_t v = 0; v < key.mesh.vertexCount(); ++v) {
    key.mesh.positions[3 * v] += static_cast<float>(amount * (1.0 + 0.1 * v));
    key.mesh.positions[3 * v + 2] += static_cast<float>(amount * std::cos(0.7 * v + frame));
  }
  key.view = view;
  key.frame = frame;
  return key;
}

const Vector3d kFront(0, 0, 1), kSide(1, 0, 0);
const std::vector<int> kFrontFrames = {3, 7, 15, 31};

RawViewDependentModel fourFrameModel(bool loop) {
  RawViewDependentModel raw = animatedSphere(loop);
  const double amounts[] = {0.1, -0.2, 0.35, 0.05};
  for (std::size_t j = 0; j < kFrontFrames.size(); ++j)
    raw.keys.push_back(keyAt(raw, "front" + std::to_string(j), kFront, kFrontFrames[j], amounts[j]));
  raw.keys.push_back(keyAt(raw, "side10", kSide, 10, 0.15));
  raw.keys.push_back(keyAt(raw, "side30", kSide, 30, -0.1));
  return raw;
}

std::vector<float> evaluated(const AnimatedViewDependentModel& model, int frame, const Vector3d& view) {
  std::vector<float> out(model.base().positions.size());
  EXPECT_TRUE(model.evaluate(frame, view, 0.0, out));
  return out;
}

// ---- Build and accessors ---------------------------------------------------------------------

TEST(AnimatedModel, KeysWithOneViewShareOneSpherePoint) {
  const auto model = AnimatedViewDependentModel::build(fourFrameModel(false));
  ASSERT_EQ(model.viewCount(), 2u);
  EXPECT_EQ(model.sphere().keyCount(), 2u);
  EXPECT_EQ(model.frameCount(), kFrames);
  const std::vector<int> front(model.keyFrames(0).begin(), model.keyFrames(0).end());
  EXPECT_EQ(front, kFrontFrames);
  const std::vector<int> side(model.keyFrames(1).begin(), model.keyFrames(1).end());
  EXPECT_EQ(side, (std::vector<int>{10, 30}));
  EXPECT_EQ(model.keyName(1, 1), "side30");
  EXPECT_EQ(model.keyIndex(1, 0), 4u);
  EXPECT_EQ(errorOf([&] { (void)model.viewDirection(2); }), "view 2 out of range (the model has 2 views)");
  EXPECT_EQ(errorOf([&] { (void)model.offsets(1, 2); }), "key frame 2 out of range (the model has 2 key frames there)");
}

TEST(AnimatedModel, KeyFramesGivenOutOfOrderAreSorted) {
  RawViewDependentModel raw = fourFrameModel(false);
  std::swap(raw.keys[0], raw.keys[3]);
  const auto model = AnimatedViewDependentModel::build(raw);
  const std::vector<int> front(model.keyFrames(0).begin(), model.keyFrames(0).end());
  EXPECT_EQ(front, kFrontFrames);
  EXPECT_EQ(model.keyName(0, 0), "front0");
}

TEST(AnimatedModel, AtAKeysFrameAndViewTheResultIsTheKeyMesh) {
  for (const bool loop : {false, true}) {
    const RawViewDependentModel raw = fourFrameModel(loop);
    const auto model = AnimatedViewDependentModel::build(raw);
    for (const RawKey& key : raw.keys) {
      const std::vector<float> out = evaluated(model, key.frame, key.view);
      for (std::size_t i = 0; i < out.size(); ++i)
        ASSERT_NEAR(out[i], key.mesh.positions[i], kKeyTol) << key.name << " loop " << loop << " index " << i;
    }
  }
}

// Offsets of vertex coordinate `i` of view `view`'s key frames.
std::vector<double> offsetData(const AnimatedViewDependentModel& model, std::size_t view, std::size_t i) {
  std::vector<double> y;
  for (std::size_t j = 0; j < model.keyFrames(view).size(); ++j) y.push_back(model.offsets(view, j)[i]);
  return y;
}

TEST(AnimatedModel, OffsetsFollowTheNaturalCubicSplineBetweenKeyFrames) {
  const RawViewDependentModel raw = fourFrameModel(false);
  const auto model = AnimatedViewDependentModel::build(raw);
  const std::vector<int> t(kFrontFrames);
  // The cardinal coefficients are the splines of the unit data e_j.
  std::vector<DirectSpline> unit;
  for (std::size_t j = 0; j < t.size(); ++j) {
    std::vector<double> e(t.size(), 0.0);
    e[j] = 1.0;
    unit.push_back(directSpline(t, e, false, kFrames));
  }
  std::vector<double> c(t.size());
  for (double x = t.front(); x <= t.back(); x += 0.25) {
    ASSERT_TRUE(model.timeCoefficients(0, x, c));
    double sum = 0.0;
    for (std::size_t j = 0; j < t.size(); ++j) {
      EXPECT_NEAR(c[j], unit[j](x), kSplineTol) << "frame " << x << " j " << j;
      sum += c[j];
    }
    EXPECT_NEAR(sum, 1.0, kSplineTol) << "a spline reproduces constants";
  }
  // evaluate() at the front view: base(f) + the spline of the actual offsets, coordinate by coordinate.
  for (int f = t.front(); f <= t.back(); ++f) {
    const std::vector<float> out = evaluated(model, f, kFront);
    for (std::size_t i = 0; i < out.size(); i += 7) {
      const DirectSpline s = directSpline(t, offsetData(model, 0, i), false, kFrames);
      EXPECT_NEAR(out[i] - raw.base_frames[static_cast<std::size_t>(f)][i], s(f), kFloatSplineTol)
          << "frame " << f << " index " << i;
    }
  }
}

TEST(AnimatedModel, OutsideTheKeyFramesTheOffsetHoldsItsEndValue) {
  const auto model = AnimatedViewDependentModel::build(fourFrameModel(false));
  std::vector<double> c(kFrontFrames.size());
  for (const double x : {-5.0, 0.0, 2.0, 3.0}) {
    ASSERT_TRUE(model.timeCoefficients(0, x, c));
    EXPECT_EQ(c, (std::vector<double>{1, 0, 0, 0})) << x;
  }
  for (const double x : {31.0, 35.5, 39.0, 1e6}) {
    ASSERT_TRUE(model.timeCoefficients(0, x, c));
    EXPECT_EQ(c, (std::vector<double>{0, 0, 0, 1})) << x;
  }
}

TEST(AnimatedModel, OneKeyFrameIsConstantAndTwoAreLinear) {
  RawViewDependentModel raw = animatedSphere(false);
  raw.keys.push_back(keyAt(raw, "one", kFront, 12, 0.2));
  raw.keys.push_back(keyAt(raw, "a", kSide, 10, 0.2));
  raw.keys.push_back(keyAt(raw, "b", kSide, 30, -0.2));
  const auto model = AnimatedViewDependentModel::build(raw);
  std::vector<double> one(1), two(2);
  for (double x = -3.0; x < kFrames + 3; x += 0.5) {
    ASSERT_TRUE(model.timeCoefficients(0, x, one));
    EXPECT_EQ(one[0], 1.0);
    ASSERT_TRUE(model.timeCoefficients(1, x, two));
    const double s = std::clamp((x - 10.0) / 20.0, 0.0, 1.0);
    EXPECT_NEAR(two[0], 1.0 - s, kSplineTol) << x;
    EXPECT_NEAR(two[1], s, kSplineTol) << x;
  }
}

TEST(AnimatedModel, LoopingOffsetsFollowThePeriodicSpline) {
  const auto model = AnimatedViewDependentModel::build(fourFrameModel(true));
  const std::vector<int> t(kFrontFrames);
  std::vector<DirectSpline> unit;
  for (std::size_t j = 0; j < t.size(); ++j) {
    std::vector<double> e(t.size(), 0.0);
    e[j] = 1.0;
    unit.push_back(directSpline(t, e, true, kFrames));
  }
  std::vector<double> c(t.size());
  for (double x = t.front(); x < t.front() + kFrames; x += 0.25) {
    ASSERT_TRUE(model.timeCoefficients(0, x, c));
    for (std::size_t j = 0; j < t.size(); ++j) EXPECT_NEAR(c[j], unit[j](x), kSplineTol) << "frame " << x;
  }
  // Any frame wraps into the cycle.
  std::vector<double> d(t.size());
  for (const double x : {0.0, 1.5, 20.0, 39.0}) {
    ASSERT_TRUE(model.timeCoefficients(0, x, c));
    for (const double shift : {-2.0 * kFrames, 1.0 * kFrames, 7.0 * kFrames}) {
      ASSERT_TRUE(model.timeCoefficients(0, x + shift, d));
      for (std::size_t j = 0; j < t.size(); ++j) EXPECT_NEAR(c[j], d[j], kSplineTol) << x << " + " << shift;
    }
  }
}

// S(x) = sum_j c_j(x) y_j for the view's real offsets (one coordinate).
double offsetAt(const AnimatedViewDependentModel& model, std::size_t view, std::size_t i, double x) {
  std::vector<double> c(model.keyFrames(view).size());
  EXPECT_TRUE(model.timeCoefficients(view, x, c));
  double s = 0.0;
  for (std::size_t j = 0; j < c.size(); ++j) s += c[j] * model.offsets(view, j)[i];
  return s;
}

TEST(AnimatedModel, PeriodicSplineClosesTheLoopWithMatchingValueSlopeAndCurvature) {
  const auto model = AnimatedViewDependentModel::build(fourFrameModel(true));
  // The cycle closes at frame N = frame 0, and the spline's own wrap is at the first key frame
  // (its last piece runs from f_m to f_1 + N); check both, for several coordinates.
  for (const double seam : {0.0, static_cast<double>(kFrontFrames.front()), static_cast<double>(kFrames)}) {
    for (std::size_t i = 0; i < 12; i += 1) {
      const auto s = [&](double x) { return offsetAt(model, 0, i, x); };
      const double h = kStep;
      EXPECT_NEAR(s(seam), s(seam + kFrames), kSeamValueTol);
      const double left_slope = (3 * s(seam) - 4 * s(seam - h) + s(seam - 2 * h)) / (2 * h);
      const double right_slope = (-3 * s(seam) + 4 * s(seam + h) - s(seam + 2 * h)) / (2 * h);
      EXPECT_NEAR(left_slope, right_slope, kSeamSlopeTol) << "seam " << seam << " index " << i;
      const double left_curv = (s(seam) - 2 * s(seam - h) + s(seam - 2 * h)) / (h * h);
      const double right_curv = (s(seam) - 2 * s(seam + h) + s(seam + 2 * h)) / (h * h);
      EXPECT_NEAR(left_curv, right_curv, kSeamCurvatureTol) << "seam " << seam << " index " << i;
    }
  }
}

TEST(AnimatedModel, WithoutLoopTheSplineDoesNotCloseTheCycle) {
  // The property above is not vacuous: the held, non-periodic offsets jump where the cycle closes.
  const auto model = AnimatedViewDependentModel::build(fourFrameModel(false));
  double largest_jump = 0.0;
  for (std::size_t i = 0; i < 12; ++i)
    largest_jump = std::max(largest_jump, std::abs(offsetAt(model, 0, i, kFrames - 1) - offsetAt(model, 0, i, 0)));
  EXPECT_GT(largest_jump, 0.01);
}

// ---- World and skinned offsets on a rotating limb --------------------------------------------
// A limb along +X from the origin, rotating about +Z by 90 degrees over the frames; every vertex's
// skin linear part is that rotation. One key (frame 0, front view) pushes the tip by +Y.
constexpr int kLimbFrames = 11;
constexpr float kPush = 0.25f;

Eigen::Matrix3d limbRotation(int frame) {
  return Eigen::AngleAxisd(0.5 * std::numbers::pi * frame / (kLimbFrames - 1), Vector3d::UnitZ()).toRotationMatrix();
}

RawViewDependentModel rotatingLimb(OffsetSpace space, int key_frame) {
  RawViewDependentModel raw;
  raw.source = "limb.vdg.json";
  // A thin strip: (0,0,0) (0,0.1,0) (1,0,0) (1,0.1,0) (2,0,0) (2,0.1,0); vertices 4 and 5 are the tip.
  for (int i = 0; i < 3; ++i)
    raw.base.positions.insert(raw.base.positions.end(), {float(i), 0.0f, 0.0f, float(i), 0.1f, 0.0f});
  raw.base.triangles = {0, 2, 3, 0, 3, 1, 2, 4, 5, 2, 5, 3};
  raw.base_animation = BaseAnimationSpec{};
  raw.base_animation->gltf = "limb.glb";
  raw.offsets = space;
  const std::vector<float> rest = raw.base.positions;
  for (int f = 0; f < kLimbFrames; ++f) {
    const Eigen::Matrix3d r = limbRotation(f);
    std::vector<float> p(rest.size()), skin;
    for (std::size_t v = 0; v < rest.size() / 3; ++v) {
      const Vector3d q = r * Vector3d(rest[3 * v], rest[3 * v + 1], rest[3 * v + 2]);
      for (int c = 0; c < 3; ++c) p[3 * v + c] = static_cast<float>(q[c]);
      for (int c = 0; c < 9; ++c) skin.push_back(static_cast<float>(r(c % 3, c / 3)));  // column-major
    }
    raw.base_frames.push_back(p);
    raw.base_skin.push_back(skin);
  }
  raw.base.positions = raw.base_frames[0];
  RawKey key;
  key.name = "push";
  key.mesh = raw.base;
  key.mesh.positions = raw.base_frames[static_cast<std::size_t>(key_frame)];
  // The push is +Y in the limb's frame at the key frame (perpendicular to the limb).
  const Vector3d push = limbRotation(key_frame) * Vector3d(0, kPush, 0);
  for (const int v : {4, 5})
    for (int c = 0; c < 3; ++c) key.mesh.positions[3 * v + c] += static_cast<float>(push[c]);
  key.view = kFront;
  key.frame = key_frame;
  raw.keys.push_back(key);
  return raw;
}

Vector3d tipOffset(const AnimatedViewDependentModel& model, int frame) {
  const std::vector<float> out = evaluated(model, frame, kFront);
  const auto base = model.baseFrame(frame);
  return {out[12] - base[12], out[13] - base[13], out[14] - base[14]};
}

TEST(AnimatedModel, SkinnedOffsetsRotateWithTheLimbWorldOffsetsStayPut) {
  constexpr double kTol = 1e-6;
  const auto world = AnimatedViewDependentModel::build(rotatingLimb(OffsetSpace::kWorld, 0));
  const auto skinned = AnimatedViewDependentModel::build(rotatingLimb(OffsetSpace::kSkinned, 0));
  for (int f = 0; f < kLimbFrames; ++f) {
    const Vector3d w = tipOffset(world, f), s = tipOffset(skinned, f);
    EXPECT_TRUE(w.isApprox(Vector3d(0, kPush, 0), kTol)) << f << ": " << w.transpose();
    EXPECT_TRUE(s.isApprox(limbRotation(f) * Vector3d(0, kPush, 0), kTol)) << f << ": " << s.transpose();
  }
  // At the end of the swing the two differ by the full 90 degrees.
  EXPECT_NEAR(tipOffset(skinned, kLimbFrames - 1).x(), -kPush, kTol);
  EXPECT_NEAR(tipOffset(skinned, kLimbFrames - 1).y(), 0.0, kTol);
}

TEST(AnimatedModel, SkinnedOffsetsAreUnskinnedAtTheirKeyFrame) {
  constexpr double kTol = 1e-6;
  const RawViewDependentModel raw = rotatingLimb(OffsetSpace::kSkinned, 6);
  const auto model = AnimatedViewDependentModel::build(raw);
  const auto o = model.offsets(0, 0);
  EXPECT_NEAR(o[12], 0.0, kTol);  // the rest-pose push is +Y
  EXPECT_NEAR(o[13], kPush, kTol);
  const std::vector<float> out = evaluated(model, 6, kFront);
  for (std::size_t i = 0; i < out.size(); ++i) EXPECT_NEAR(out[i], raw.keys[0].mesh.positions[i], kKeyTol);
  // World offsets at frame 0 keep the key frame's world direction instead.
  const auto world = AnimatedViewDependentModel::build(rotatingLimb(OffsetSpace::kWorld, 6));
  EXPECT_TRUE(tipOffset(world, 0).isApprox(limbRotation(6) * Vector3d(0, kPush, 0), kTol));
  EXPECT_TRUE(tipOffset(model, 0).isApprox(Vector3d(0, kPush, 0), kTol));
}

// ---- extent(): what the model can draw at any frame -----------------------------------------------

// The union box of `positions` meshes and the farthest vertex from `center`.
struct UnionExtent {
  Bounds box;
  double radius = 0.0;
  bool empty = true;
  void add(std::span<const float> positions, const Vector3d& center) {
    const Bounds b = computeBounds(positions);
    for (int c = 0; c < 3; ++c) {
      box.min[c] = empty ? b.min[c] : std::min(box.min[c], b.min[c]);
      box.max[c] = empty ? b.max[c] : std::max(box.max[c], b.max[c]);
    }
    empty = false;
    for (std::size_t v = 0; v < positions.size() / 3; ++v)
      radius =
          std::max(radius, (Vector3d(positions[3 * v], positions[3 * v + 1], positions[3 * v + 2]) - center).norm());
  }
};

void expectInsideExtent(const AnimatedViewDependentModel& model, std::span<const float> positions,
                        const std::string& what) {
  const Bounds& box = model.extent();
  for (std::size_t v = 0; v < positions.size() / 3; ++v) {
    for (int c = 0; c < 3; ++c) {
      ASSERT_GE(positions[3 * v + c], box.min[c] - kFloatSplineTol) << what << " vertex " << v;
      ASSERT_LE(positions[3 * v + c], box.max[c] + kFloatSplineTol) << what << " vertex " << v;
    }
    const Vector3d p(positions[3 * v], positions[3 * v + 1], positions[3 * v + 2]);
    ASSERT_LE((p - model.center()).norm(), model.extentRadius() + kFloatSplineTol) << what << " vertex " << v;
  }
}

// Both offset spaces: the extent holds the base at every frame and every key mesh, every frame seen
// from views all around stays inside it, and it is no larger than the base frames and the views'
// full poses (a key view's weight is 1) need.
TEST(AnimatedModelExtent, HoldsEveryFrameEveryKeyAndEveryBlend) {
  for (const RawViewDependentModel& raw :
       {fourFrameModel(false), fourFrameModel(true), rotatingLimb(OffsetSpace::kSkinned, 4)}) {
    SCOPED_TRACE(raw.source + (raw.base_animation->loop ? " loop" : ""));
    const AnimatedViewDependentModel model = AnimatedViewDependentModel::build(raw);
    UnionExtent needed;
    for (int f = 0; f < model.frameCount(); ++f) {
      expectInsideExtent(model, model.baseFrame(f), "base frame " + std::to_string(f));
      needed.add(model.baseFrame(f), model.center());
      for (std::size_t v = 0; v < model.viewCount(); ++v)
        needed.add(evaluated(model, f, model.viewDirection(v)), model.center());
    }
    for (const RawKey& key : raw.keys) expectInsideExtent(model, key.mesh.positions, "key " + key.name);
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(model.extent().min[c], needed.box.min[c], kFloatSplineTol) << c;
      EXPECT_NEAR(model.extent().max[c], needed.box.max[c], kFloatSplineTol) << c;
    }
    EXPECT_NEAR(model.extentRadius(), needed.radius, kFloatSplineTol);
    for (int f = 0; f < model.frameCount(); f += 3)
      for (int i = 0; i < 24; ++i) {
        const double az = 2.0 * std::numbers::pi * i / 24, el = 0.6 * std::sin(1.7 * i);
        const Vector3d view(std::sin(az) * std::cos(el), std::sin(el), std::cos(az) * std::cos(el));
        expectInsideExtent(model, evaluated(model, f, view), "frame " + std::to_string(f));
      }
  }
}

// A key offset held past its frame moves with the base: the extent follows the base's bobbing with
// the offset on, beyond the base's own frames.
TEST(AnimatedModelExtent, GrowsPastTheBaseFramesWhenAKeyMovesOutward) {
  RawViewDependentModel raw = animatedSphere(false);
  RawKey key = keyAt(raw, "up", kFront, 5, 0.0);
  for (std::size_t v = 0; v < key.mesh.vertexCount(); ++v) key.mesh.positions[3 * v + 1] += 0.5f;
  raw.keys.push_back(key);
  const AnimatedViewDependentModel model = AnimatedViewDependentModel::build(raw);
  UnionExtent bases;
  for (int f = 0; f < model.frameCount(); ++f) bases.add(model.baseFrame(f), model.center());
  // One key frame: the offset (+0.5 in y) is constant, so the top of the extent is the bases' + 0.5.
  EXPECT_NEAR(model.extent().max[1], bases.box.max[1] + 0.5f, kFloatSplineTol);
  EXPECT_NEAR(model.extent().min[1], bases.box.min[1], kFloatSplineTol);
}

TEST(AnimatedModel, EvaluatePosedMatchesEvaluateAtIntegerFrames) {
  const auto model = AnimatedViewDependentModel::build(rotatingLimb(OffsetSpace::kSkinned, 3));
  const Vector3d view(0.3, 0.2, 1.0);
  std::vector<float> a(model.base().positions.size()), b(a.size()), na(a.size()), nb(a.size());
  for (int f = 0; f < kLimbFrames; ++f) {
    ASSERT_TRUE(model.evaluate(f, view, 0.0, a, na));
    ASSERT_TRUE(model.evaluatePosed(f, model.baseFrame(f), model.baseSkin(f), view, 0.0, b, nb));
    EXPECT_EQ(a, b);
    EXPECT_EQ(na, nb);
  }
}

// ---- The per-frame contract ------------------------------------------------------------------

constexpr float kSentinel = -12345.5f;

TEST(AnimatedModelContract, InvalidInputIsRefusedAndWritesNothing) {
  const auto model = AnimatedViewDependentModel::build(rotatingLimb(OffsetSpace::kSkinned, 0));
  const std::size_t n = model.base().positions.size();
  std::vector<float> out(n, kSentinel), normals(n, kSentinel);
  int hint = 424242;
  const auto untouched = [&] {
    for (float x : out) ASSERT_EQ(x, kSentinel);
    for (float x : normals) ASSERT_EQ(x, kSentinel);
    ASSERT_EQ(hint, 424242);
  };
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(model.evaluate(-1, kFront, 0.0, out, normals, &hint));
  EXPECT_FALSE(model.evaluate(kLimbFrames, kFront, 0.0, out, normals, &hint));
  EXPECT_FALSE(model.evaluate(0, Vector3d::Zero(), 0.0, out, normals, &hint));
  EXPECT_FALSE(model.evaluate(0, kFront, nan, out, normals, &hint));
  EXPECT_FALSE(model.evaluate(0, kFront, 0.0, std::span<float>(out).first(n - 1), normals, &hint));
  EXPECT_FALSE(model.evaluate(0, kFront, 0.0, out, std::span<float>(normals).first(3), &hint));
  const auto base = model.baseFrame(0);
  const auto skin = model.baseSkin(0);
  EXPECT_FALSE(model.evaluatePosed(nan, base, skin, kFront, 0.0, out, normals, &hint));
  EXPECT_FALSE(model.evaluatePosed(0.5, base.first(n - 3), skin, kFront, 0.0, out, normals, &hint));
  EXPECT_FALSE(model.evaluatePosed(0.5, base, {}, kFront, 0.0, out, normals, &hint));  // skinned needs it
  EXPECT_FALSE(model.evaluatePosed(0.5, base, skin.first(9), kFront, 0.0, out, normals, &hint));
  int bad_hint = 1000000;
  EXPECT_FALSE(model.evaluatePosed(0.5, base, skin, kFront, 0.0, out, normals, &bad_hint));
  untouched();
  std::vector<double> c(1, -7.0);
  EXPECT_FALSE(model.timeCoefficients(1, 0.0, c));
  EXPECT_FALSE(model.timeCoefficients(0, nan, c));
  std::vector<double> c2(2, -7.0);
  EXPECT_FALSE(model.timeCoefficients(0, 0.0, c2));
  EXPECT_EQ(c[0], -7.0);
  EXPECT_EQ(c2, (std::vector<double>{-7.0, -7.0}));

  // World offsets: the skin is optional (empty or #V x 9), anything else is refused.
  const auto world = AnimatedViewDependentModel::build(rotatingLimb(OffsetSpace::kWorld, 0));
  EXPECT_TRUE(world.evaluatePosed(0.5, base, {}, kFront, 0.0, out));
  EXPECT_TRUE(world.evaluatePosed(0.5, base, skin, kFront, 0.0, out));
  std::fill(out.begin(), out.end(), kSentinel);
  EXPECT_FALSE(world.evaluatePosed(0.5, base, skin.first(9), kFront, 0.0, out, normals, &hint));
  untouched();
}

TEST(AnimatedModelContract, EvaluationAllocatesNothing) {
  const auto model = AnimatedViewDependentModel::build(fourFrameModel(true));
  const auto skinned = AnimatedViewDependentModel::build(rotatingLimb(OffsetSpace::kSkinned, 2));
  std::vector<float> out(model.base().positions.size()), normals(out.size());
  std::vector<float> out2(skinned.base().positions.size()), normals2(out2.size());
  std::vector<double> c(kFrontFrames.size());
  int hint = -1;
  const long allocations = testing::allocationsDuring([&] {
    for (int f = 0; f < 2 * kFrames; ++f) {
      const Vector3d view(std::sin(0.1 * f), 0.2, std::cos(0.1 * f));
      (void)model.evaluate(f % kFrames, view, 0.0, out, normals, &hint);
      (void)model.evaluatePosed(f * 0.37, model.baseFrame(f % kFrames), {}, view, 2.0, out, normals, &hint);
      (void)model.timeCoefficients(0, f * 0.61, c);
      (void)skinned.evaluate(f % kLimbFrames, view, 0.0, out2, normals2);
      (void)model.evaluate(-1, view, 0.0, out, normals, &hint);  // refused
    }
  });
  EXPECT_EQ(allocations, 0);
}

// ---- Validation of raw animated models --------------------------------------------------------

TEST(AnimatedModelValidate, SameViewAndSameFrameIsAnError) {
  RawViewDependentModel raw = fourFrameModel(false);
  raw.keys.push_back(keyAt(raw, "again", kFront * 3.0, 15, 0.1));
  EXPECT_EQ(errorOf([&] { raw.validate(); }),
            "anim.vdg.json: key 'again' (keys[6]): same view direction (within 1e-6 rad) and same frame 15 as key "
            "'front2'");
}

TEST(AnimatedModelValidate, BadFramesAndBaseData) {
  RawViewDependentModel raw = fourFrameModel(false);
  raw.keys[1].frame = kFrames;
  EXPECT_EQ(errorOf([&] { raw.validate(); }),
            "anim.vdg.json: key 'front1' (keys[1]): frame 40 is outside the base animation's frames 0..39");
  raw.keys[1].frame = -1;
  EXPECT_EQ(errorOf([&] { raw.validate(); }),
            "anim.vdg.json: key 'front1' (keys[1]): frame -1 is outside the base animation's frames 0..39");

  raw = fourFrameModel(false);
  raw.base_frames[5].pop_back();
  EXPECT_EQ(errorOf([&] { raw.validate(); }),
            "anim.vdg.json: base animation frame 5 has 59 coordinates; expected 3 per vertex of the base (60)");
  raw = fourFrameModel(false);
  raw.base_frames[5][7] = std::numeric_limits<float>::infinity();
  EXPECT_EQ(errorOf([&] { raw.validate(); }),
            "anim.vdg.json: base animation frame 5: vertex 2 has a non-finite coordinate (NaN or Inf)");
  raw = fourFrameModel(false);
  raw.base_frames.clear();
  EXPECT_EQ(errorOf([&] { raw.validate(); }), "anim.vdg.json: the base animation has no frames");
  raw = fourFrameModel(false);
  raw.base_skin.assign(3, {});
  EXPECT_EQ(errorOf([&] { raw.validate(); }), "anim.vdg.json: base_skin has 3 frames but the base animation has 40");
  raw.base_skin.assign(kFrames, std::vector<float>(9));
  EXPECT_EQ(errorOf([&] { raw.validate(); }),
            "anim.vdg.json: base_skin frame 0 has 9 floats; expected 9 per vertex (180)");
  raw = fourFrameModel(false);
  raw.offsets = OffsetSpace::kSkinned;
  EXPECT_EQ(errorOf([&] { raw.validate(); }),
            "anim.vdg.json: 'offsets': 'skinned' needs a skinned base (the base animation has no skin)");
}

TEST(AnimatedModelValidate, SingularSkinAtAKeyFrameNamesTheVertex) {
  RawViewDependentModel raw = rotatingLimb(OffsetSpace::kSkinned, 4);
  for (int c = 0; c < 9; ++c) raw.base_skin[4][9 * 3 + c] = c < 3 ? 0.0f : raw.base_skin[4][9 * 3 + c];
  EXPECT_EQ(errorOf([&] { raw.validate(); }),
            "limb.vdg.json: key 'push' (keys[0]): vertex 3: the skin matrix at frame 4 is singular, so 'offsets': "
            "'skinned' cannot un-skin the offset");
  // Singular elsewhere than at a key frame, or with world offsets: fine.
  raw.keys[0].frame = 0;
  raw.keys[0].mesh.positions = raw.base_frames[0];
  EXPECT_EQ(errorOf([&] { raw.validate(); }), "");
  raw.keys[0].frame = 4;
  raw.offsets = OffsetSpace::kWorld;
  EXPECT_EQ(errorOf([&] { raw.validate(); }), "");
}

TEST(AnimatedModelValidate, StaticModelsRefuseAnimationFields) {
  RawViewDependentModel raw;
  raw.source = "m.vdg.json";
  raw.base = testing::uvSphere(4, 6);
  RawKey key;
  key.name = "k";
  key.mesh = raw.base;
  key.view = kFront;
  key.frame = 2;
  raw.keys.push_back(key);
  EXPECT_EQ(errorOf([&] { raw.validate(); }),
            "m.vdg.json: key 'k' (keys[0]): frame 2 needs an animated base ('base_animation'); a static base has "
            "only frame 0");
  raw.keys[0].frame = 0;
  raw.offsets = OffsetSpace::kSkinned;
  EXPECT_EQ(errorOf([&] { raw.validate(); }),
            "m.vdg.json: 'offsets': 'skinned' needs an animated, skinned base ('base_animation')");
  raw.offsets = OffsetSpace::kWorld;
  raw.base_frames.push_back(raw.base.positions);
  EXPECT_EQ(errorOf([&] { raw.validate(); }),
            "m.vdg.json: base_frames are given but the base is static (no 'base_animation')");
  raw.base_frames.clear();
  EXPECT_EQ(errorOf([&] { (void)AnimatedViewDependentModel::build(raw); }),
            "m.vdg.json: the base is not animated (no 'base_animation'); build it as a ViewDependentModel");
  EXPECT_EQ(errorOf([&] { (void)ViewDependentModel::build(fourFrameModel(false)); }),
            "anim.vdg.json: has an animated base ('base_animation'); build it as an AnimatedViewDependentModel "
            "(vdg/viewdep/animated_model.h)");
  RawViewDependentModel empty = fourFrameModel(false);
  empty.keys.clear();
  EXPECT_EQ(errorOf([&] { (void)AnimatedViewDependentModel::build(empty); }),
            "anim.vdg.json: the model has no keys (add at least one key deformation)");
}

TEST(AnimatedModelValidate, TooManyKeyFramesForOneView) {
  RawViewDependentModel raw = animatedSphere(false);
  raw.base_frames.resize(kMaxKeyFramesPerView + 1, raw.base_frames[0]);
  for (std::size_t f = 0; f <= kMaxKeyFramesPerView; ++f)
    raw.keys.push_back(keyAt(raw, "k" + std::to_string(f), kFront, static_cast<int>(f), 0.0));
  EXPECT_EQ(errorOf([&] { raw.validate(); }),
            "anim.vdg.json: key 'k0' (keys[0]): its view has 257 key frames; one view may have at most 256");
}

}  // namespace
}  // namespace vdg
