// Tests of orientation representations, slerp and quaternion curves (Parent 4.3).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "vdg/anim/quaternion_curve.h"
#include "vdg/anim/rotation.h"
#include "vdg/geom/error.h"

namespace vdg::anim {
namespace {

constexpr double kTol = 1e-12;
constexpr double kAngleTol = 1e-9;
constexpr double kDeg = std::numbers::pi / 180.0;

Eigen::Vector3d deg(double x, double y, double z) { return Eigen::Vector3d(x, y, z) * kDeg; }

TEST(Rotation, FixedAnglesAreXThenYThenZAboutWorldAxes) {
  const Eigen::Vector3d angles = deg(10, 45, 90);
  const Eigen::Matrix3d r = fixedAnglesToMatrix(angles);
  EXPECT_LT((r - rotationZ(90 * kDeg) * rotationY(45 * kDeg) * rotationX(10 * kDeg)).norm(), kTol);
  // Euler z-y-x (about the moving axes) is the same matrix: Rz * Ry' * Rx''.
  EXPECT_LT((eulerZyxToMatrix(Eigen::Vector3d(90, 45, 10) * kDeg) - r).norm(), kTol);
  // The text's derivation: a rotation about a once-rotated axis y' = Rx y.
  const Eigen::Matrix3d rx = rotationX(10 * kDeg);
  const Eigen::Matrix3d ry_prime = rx * rotationY(45 * kDeg) * rx.transpose();
  EXPECT_LT((ry_prime * rx - rx * rotationY(45 * kDeg)).norm(), kTol);
  EXPECT_LT((matrixToFixedAngles(r) - angles).norm(), kAngleTol);
  EXPECT_LT((matrixToEulerZyx(r) - Eigen::Vector3d(90, 45, 10) * kDeg).norm(), kAngleTol);
  // Agrees with Eigen's own (intrinsic z-y-x) Euler angles.
  EXPECT_LT((r - Eigen::Matrix3d(Eigen::AngleAxisd(90 * kDeg, Eigen::Vector3d::UnitZ()) *
                                 Eigen::AngleAxisd(45 * kDeg, Eigen::Vector3d::UnitY()) *
                                 Eigen::AngleAxisd(10 * kDeg, Eigen::Vector3d::UnitX())))
                .norm(),
            kTol);
}

TEST(Rotation, ConversionsRoundTrip) {
  for (const Eigen::Vector3d& a : {deg(10, 45, 90), deg(-30, 20, 170), deg(0, 0, 0), deg(5, -80, -45)}) {
    const Eigen::Matrix3d r = fixedAnglesToMatrix(a);
    const Quaternion q = fixedAnglesToQuaternion(a);
    EXPECT_NEAR(q.norm(), 1.0, kTol);
    EXPECT_LT((quaternionToMatrix(q) - r).norm(), 1e-12);
    EXPECT_TRUE(sameRotation(matrixToQuaternion(r), q));
    EXPECT_LT((quaternionToFixedAngles(q) - a).norm(), 1e-9);
    Eigen::Vector3d axis;
    double angle = 0;
    quaternionToAxisAngle(q, &axis, &angle);
    EXPECT_TRUE(sameRotation(axisAngleToQuaternion(axis, angle), q));
    const Eigen::Matrix4d m = toMatrix4(r, Eigen::Vector3d(1, 2, 3));
    EXPECT_LT((rotationPart(m) - r).norm(), kTol);
    EXPECT_EQ(translationPart(m), Eigen::Vector3d(1, 2, 3));
    const Eigen::Vector3d p(0.3, -1, 2);
    EXPECT_LT(((m * p.homogeneous()).head<3>() - (r * p + Eigen::Vector3d(1, 2, 3))).norm(), kTol);
  }
  // Gimbal lock: beta = 90 degrees, alpha and gamma not separable; the matrix is reproduced.
  const Eigen::Matrix3d locked = fixedAnglesToMatrix(deg(30, 90, 10));
  EXPECT_LT((fixedAnglesToMatrix(matrixToFixedAngles(locked)) - locked).norm(), 1e-9);
  EXPECT_NEAR(matrixToFixedAngles(locked).y(), 90 * kDeg, 1e-9);
}

TEST(Quaternion, ProductInverseAndRotationFollowTheText) {
  const Quaternion q1(0.3, -0.2, 0.9, 0.1), q2(-0.5, 0.4, 0.2, 0.7);
  // [s1,v1][s2,v2] = [s1 s2 - v1.v2, s1 v2 + s2 v1 + v1 x v2]
  EXPECT_LT((multiply(q1, q2).coeffs() - (q1 * q2).coeffs()).norm(), kTol);
  const Quaternion one = multiply(q1, inverse(q1));
  EXPECT_LT((one.coeffs() - Quaternion::Identity().coeffs()).norm(), kTol);
  // Rotation of a vector; scalar multiples (including -q) give the same rotation.
  const Quaternion q = axisAngleToQuaternion(Eigen::Vector3d(0, 0, 1), 90 * kDeg);
  EXPECT_LT((rotate(q, Eigen::Vector3d(1, 0, 0)) - Eigen::Vector3d(0, 1, 0)).norm(), kTol);
  Quaternion minus_q(-q.coeffs()), scaled(3.0 * q.coeffs());
  EXPECT_LT((rotate(minus_q, Eigen::Vector3d(1, 2, 3)) - rotate(q, Eigen::Vector3d(1, 2, 3))).norm(), kTol);
  EXPECT_LT((rotate(scaled, Eigen::Vector3d(1, 2, 3)) - rotate(q, Eigen::Vector3d(1, 2, 3))).norm(), 1e-12);
  EXPECT_TRUE(sameRotation(q, minus_q));
  // Cross products are preserved: Rot(v1) x Rot(v2) = Rot(v1 x v2).
  const Eigen::Vector3d v1(1, 2, 3), v2(-2, 0.5, 1);
  const Quaternion u = q1.normalized();
  EXPECT_LT((rotate(u, v1).cross(rotate(u, v2)) - rotate(u, v1.cross(v2))).norm(), 1e-12);
  EXPECT_LT((rotate(u, v1) - quaternionToMatrix(u) * v1).norm(), 1e-12);
  // q = Rot(axis, theta) = [cos(theta/2), sin(theta/2) axis]
  EXPECT_NEAR(q.w(), std::cos(45 * kDeg), kTol);
  EXPECT_NEAR(q.z(), std::sin(45 * kDeg), kTol);
}

TEST(Slerp, FormsAgreeAndHalfwayIsTheNormalisedSum) {
  const Quaternion q1 = fixedAnglesToQuaternion(deg(10, 20, 30));
  const Quaternion q2 = fixedAnglesToQuaternion(deg(-40, 60, 100));
  ASSERT_GT(q1.coeffs().dot(q2.coeffs()), 0.0);
  for (double u : {0.0, 0.25, 0.5, 0.8, 1.0}) {
    const Quaternion a = slerp(q1, q2, u), b = slerpGroupForm(q1, q2, u);
    EXPECT_NEAR(a.norm(), 1.0, kTol);
    EXPECT_TRUE(sameRotation(a, b, 1e-12)) << u;
    EXPECT_NEAR(angleBetween(q1, a), u * angleBetween(q1, q2), 1e-9);  // constant angular speed
  }
  EXPECT_LT((slerp(q1, q2, 0.5).coeffs() - (q1.coeffs() + q2.coeffs()).normalized()).norm(), kTol);
  // Shortest arc: -q2 gives the same path.
  const Quaternion minus_q2(-q2.coeffs());
  EXPECT_TRUE(sameRotation(slerp(q1, minus_q2, 0.3), slerp(q1, q2, 0.3), 1e-12));
  EXPECT_LT((slerp(q1, minus_q2, 0.5).coeffs() - (q1.coeffs() + q2.coeffs()).normalized()).norm(), kTol);
  // Identical inputs.
  EXPECT_TRUE(sameRotation(slerp(q1, q1, 0.4), q1));
}

TEST(Slerp, GimbalLockExampleOfTheText) {
  // Keys (0, 90, 0) and (90, 45, 90) in fixed angles: the second is a 45-degree rotation about x
  // from the first.
  const Eigen::Matrix3d m1 = fixedAnglesToMatrix(deg(0, 90, 0));
  const Eigen::Matrix3d m2 = fixedAnglesToMatrix(deg(90, 45, 90));
  EXPECT_LT((m2 - rotationX(45 * kDeg) * m1).norm(), 1e-12);
  // Interpolating the angles gives (45, 67.5, 45) half-way, which is not on that x rotation.
  const Eigen::Vector3d angle_mid = (deg(0, 90, 0) + deg(90, 45, 90)) / 2;
  EXPECT_LT((angle_mid - deg(45, 67.5, 45)).norm(), kTol);
  const Eigen::Matrix3d intended_mid = rotationX(22.5 * kDeg) * m1;
  EXPECT_GT((fixedAnglesToMatrix(angle_mid) - intended_mid).norm(), 0.1);
  // Slerp follows the intended path: at every u a rotation about world x by 45 u degrees from the
  // first key. Half-way that is fixed angles (90, 67.5, 90): Rz(90) Ry(b) Rx(90) = Rx(90 - b) Ry(90).
  // The text prints (90, 22.5, 90) as the desired half-way orientation, but that one is a 67.5-degree
  // x rotation from the first key (not between the keys); we test the orientation the text describes.
  const Quaternion q1 = matrixToQuaternion(m1), q2 = matrixToQuaternion(m2);
  for (double u : {0.0, 0.25, 0.5, 0.75, 1.0}) {
    EXPECT_LT((quaternionToMatrix(slerp(q1, q2, u)) - rotationX(45 * u * kDeg) * m1).norm(), 1e-12) << u;
  }
  EXPECT_LT((quaternionToMatrix(slerp(q1, q2, 0.5)) - fixedAnglesToMatrix(deg(90, 67.5, 90))).norm(), 1e-12);
  EXPECT_LT((quaternionToFixedAngles(slerp(q1, q2, 0.5)) - deg(90, 67.5, 90)).norm(), 1e-9);
  EXPECT_LT((fixedAnglesToMatrix(deg(90, 22.5, 90)) - rotationX(67.5 * kDeg) * m1).norm(), 1e-12);
}

TEST(QuaternionCurve, InterpolatesKeysStaysUnitAndIsSmooth) {
  const std::vector<Quaternion> keys = {fixedAnglesToQuaternion(deg(0, 0, 0)), fixedAnglesToQuaternion(deg(30, 10, 0)),
                                        Quaternion(-fixedAnglesToQuaternion(deg(60, 40, 20)).coeffs()),
                                        fixedAnglesToQuaternion(deg(90, 20, 70)),
                                        fixedAnglesToQuaternion(deg(100, 0, 120))};
  const std::vector<double> times = {0, 1, 2, 3, 4};
  const QuaternionCurve c = QuaternionCurve::build(keys, times);
  for (std::size_t i = 0; i < keys.size(); ++i) EXPECT_TRUE(sameRotation(c.at(times[i]), keys[i], 1e-12));
  for (double t = 0; t <= 4.0; t += 0.01) EXPECT_NEAR(c.at(t).norm(), 1.0, kTol);
  // C1 at interior keys: angular velocity on both sides agrees (equal key spacing).
  const double h = 1e-5;
  for (double t : {1.0, 2.0, 3.0}) {
    const double left = angleBetween(c.at(t - h), c.at(t)) / h;
    const double right = angleBetween(c.at(t), c.at(t + h)) / h;
    EXPECT_NEAR(left, right, 1e-3 * std::max(1.0, left)) << t;
    // ...and the same axis of angular velocity.
    const Quaternion dl = multiply(c.at(t), inverse(c.at(t - h)));
    const Quaternion dr = multiply(c.at(t + h), inverse(c.at(t)));
    EXPECT_GT(dl.vec().normalized().dot(dr.vec().normalized() * (dl.w() * dr.w() > 0 ? 1 : -1)), 1 - 1e-4);
  }
  // Control points follow the construction: b_i mirrors a_i about q_i.
  for (int i = 1; i < 4; ++i) {
    const Quaternion& q = c.keys()[i];
    EXPECT_TRUE(sameRotation(multiply(multiply(q, inverse(c.controlsAfter()[i])), q), c.controlsBefore()[i], 1e-12));
  }
}

TEST(QuaternionCurve, KeysOnOneGreatArcReproduceSlerp) {
  const Quaternion a = axisAngleToQuaternion(Eigen::Vector3d(1, 1, 0), 0.0);
  std::vector<Quaternion> keys;
  for (int i = 0; i < 5; ++i) keys.push_back(axisAngleToQuaternion(Eigen::Vector3d(1, 1, 0), 0.4 * i));
  const QuaternionCurve c = QuaternionCurve::build(keys);
  for (double t = 0; t <= 4.0; t += 0.1) {
    EXPECT_TRUE(sameRotation(c.at(t), slerp(a, keys[4], t / 4), 1e-9)) << t;
  }
  // Two keys: plain slerp.
  const QuaternionCurve two = QuaternionCurve::build({keys[0], keys[3]}, {0, 2});
  EXPECT_TRUE(sameRotation(two.at(0.5), slerp(keys[0], keys[3], 0.25), 1e-12));
  // The text's literal control points (control_fraction = 1): a_n = slerp(extend(q_{n-1}, q_n), q_{n+1}, 1/2).
  const QuaternionCurve literal = QuaternionCurve::build(keys, {}, {1.0});
  EXPECT_TRUE(sameRotation(literal.controlsAfter()[1], slerp(extend(keys[0], keys[1]), keys[2], 0.5), 1e-12));
  for (std::size_t i = 0; i < keys.size(); ++i) EXPECT_TRUE(sameRotation(literal.at(double(i)), keys[i], 1e-12));
}

TEST(QuaternionCurve, DeCasteljauWithSlerp) {
  const Quaternion q0 = fixedAnglesToQuaternion(deg(0, 0, 0)), a = fixedAnglesToQuaternion(deg(20, 0, 0));
  const Quaternion b = fixedAnglesToQuaternion(deg(40, 10, 0)), q1 = fixedAnglesToQuaternion(deg(60, 10, 5));
  const double u = 0.25;
  const Quaternion p1 = slerp(q0, a, u), p2 = slerp(a, b, u), p3 = slerp(b, q1, u);
  const Quaternion p = slerp(slerp(p1, p2, u), slerp(p2, p3, u), u);
  EXPECT_TRUE(sameRotation(sphericalBezier(q0, a, b, q1, u), p, kTol));
}

TEST(QuaternionCurve, RejectsInvalidInput) {
  auto expect = [](auto f, const std::string& message) {
    try {
      f();
      FAIL() << message;
    } catch (const Error& e) {
      EXPECT_EQ(std::string(e.what()), message);
    }
  };
  const Quaternion id = Quaternion::Identity();
  expect([&] { QuaternionCurve::build({id}); }, "quaternion curve: needs at least 2 key orientations, got 1");
  expect(
      [&] {
        QuaternionCurve::build({id, Quaternion(0, 0, 0, 0)});
      },
      "quaternion curve: key 1: quaternion must be finite and non-zero");
  expect(
      [&] {
        QuaternionCurve::build({id, id}, {0, 0});
      },
      "quaternion curve: 'times'[1]: key times must be finite and strictly increase");
  expect([&] { QuaternionCurve::build({id, id}, {0}); }, "quaternion curve: 'times': expected 2 key times, got 1");
  expect(
      [&] {
        QuaternionCurve::build({id, id}, {}, {0.0});
      },
      "quaternion curve: 'control_fraction' must be in (0, 1], got 0");
}

}  // namespace
}  // namespace vdg::anim
