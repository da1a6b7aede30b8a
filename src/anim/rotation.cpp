// Orientation representation and interpolation — Parent, Computer Animation, section 4.3
// (fixed angles, Euler angles, axis-angle, quaternions, slerp). K. Shoemake, "Animating rotation
// with quaternion curves", SIGGRAPH 85, for the slerp formulas the text quotes.
#include "vdg/anim/rotation.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "vdg/geom/normalize.h"

namespace vdg::anim {
namespace {

constexpr double kSlerpLinearThreshold = 1e-6;  // below this angle slerp falls back to nlerp

// Robust (vdg/geom/normalize.h): a quaternion 1e200 or 1e-200 long keeps its rotation.
Quaternion normalised(const Quaternion& q) { return vdg::normalizedOrNone(q).value_or(Quaternion::Identity()); }

}  // namespace

Eigen::Matrix3d rotationX(double a) {
  const double c = std::cos(a), s = std::sin(a);
  Eigen::Matrix3d r;
  r << 1, 0, 0, 0, c, -s, 0, s, c;
  return r;
}

Eigen::Matrix3d rotationY(double a) {
  const double c = std::cos(a), s = std::sin(a);
  Eigen::Matrix3d r;
  r << c, 0, s, 0, 1, 0, -s, 0, c;
  return r;
}

Eigen::Matrix3d rotationZ(double a) {
  const double c = std::cos(a), s = std::sin(a);
  Eigen::Matrix3d r;
  r << c, -s, 0, s, c, 0, 0, 0, 1;
  return r;
}

// Parent 4.3 fixed angles: Rx(alpha) Ry(beta) Rz(gamma) in the text's row-vector notation.
Eigen::Matrix3d fixedAnglesToMatrix(const Eigen::Vector3d& xyz) {
  return rotationZ(xyz.z()) * rotationY(xyz.y()) * rotationX(xyz.x());
}

Eigen::Vector3d matrixToFixedAngles(const Eigen::Matrix3d& r) {
  // R = Rz(g) Ry(b) Rx(a): r20 = -sin b, r21 = cos b sin a, r22 = cos b cos a,
  // r10 = sin g cos b, r00 = cos g cos b.
  const double sb = std::clamp(-r(2, 0), -1.0, 1.0);
  const double cb = std::sqrt(r(2, 1) * r(2, 1) + r(2, 2) * r(2, 2));
  if (cb > 1e-9) {
    return {std::atan2(r(2, 1), r(2, 2)), std::atan2(sb, cb), std::atan2(r(1, 0), r(0, 0))};
  }
  // Gimbal lock: gamma = 0, then R = Ry(+-pi/2) Rx(a): r01 = sin b sin a, r11 = cos a.
  const double alpha = std::atan2(sb > 0 ? r(0, 1) : -r(0, 1), r(1, 1));
  return {alpha, sb > 0 ? std::numbers::pi / 2 : -std::numbers::pi / 2, 0.0};
}

// Parent 4.3: Rx(a) R'y(b) R''z(g) = Rz(g) Ry(b) Rx(a) in row-vector notation, i.e. Euler angles
// in one order equal fixed angles in the reverse order.
Eigen::Matrix3d eulerZyxToMatrix(const Eigen::Vector3d& zyx) {
  return fixedAnglesToMatrix(Eigen::Vector3d(zyx.z(), zyx.y(), zyx.x()));
}

Eigen::Vector3d matrixToEulerZyx(const Eigen::Matrix3d& r) {
  const Eigen::Vector3d xyz = matrixToFixedAngles(r);
  return {xyz.z(), xyz.y(), xyz.x()};
}

Eigen::Matrix4d toMatrix4(const Eigen::Matrix3d& rotation, const Eigen::Vector3d& translation) {
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  m.topLeftCorner<3, 3>() = rotation;
  m.topRightCorner<3, 1>() = translation;
  return m;
}

Eigen::Matrix3d rotationPart(const Eigen::Matrix4d& m) { return m.topLeftCorner<3, 3>(); }
Eigen::Vector3d translationPart(const Eigen::Matrix4d& m) { return m.topRightCorner<3, 1>(); }

// Parent 4.3: Rot((x,y,z), theta) = [cos(theta/2), sin(theta/2) (x,y,z)].
Quaternion axisAngleToQuaternion(const Eigen::Vector3d& axis, double angle) {
  const std::optional<Eigen::Vector3d> unit = vdg::normalizedOrNone(axis);  // any finite length
  if (!unit) return Quaternion::Identity();
  const Eigen::Vector3d v = *unit * std::sin(angle / 2);
  return Quaternion(std::cos(angle / 2), v.x(), v.y(), v.z());
}

void quaternionToAxisAngle(const Quaternion& q_in, Eigen::Vector3d* axis, double* angle) {
  Quaternion q = normalised(q_in);
  if (q.w() < 0) q.coeffs() = -q.coeffs();  // same rotation, angle in [0, pi]
  const double s = q.vec().norm();
  *angle = 2.0 * std::atan2(s, q.w());
  *axis = s > 0.0 ? Eigen::Vector3d(q.vec() / s) : Eigen::Vector3d::UnitX();
}

Quaternion matrixToQuaternion(const Eigen::Matrix3d& r) {
  Quaternion q(r);
  q.normalize();
  if (q.w() < 0) q.coeffs() = -q.coeffs();
  return q;
}

Eigen::Matrix3d quaternionToMatrix(const Quaternion& q) { return normalised(q).toRotationMatrix(); }

Quaternion fixedAnglesToQuaternion(const Eigen::Vector3d& xyz) {
  // Rz(g) Ry(b) Rx(a) as a product of three axis-angle quaternions.
  return multiply(multiply(axisAngleToQuaternion(Eigen::Vector3d::UnitZ(), xyz.z()),
                           axisAngleToQuaternion(Eigen::Vector3d::UnitY(), xyz.y())),
                  axisAngleToQuaternion(Eigen::Vector3d::UnitX(), xyz.x()));
}

Eigen::Vector3d quaternionToFixedAngles(const Quaternion& q) { return matrixToFixedAngles(quaternionToMatrix(q)); }

// Parent 4.3: [s1,v1][s2,v2] = [s1 s2 - v1.v2, s1 v2 + s2 v1 + v1 x v2].
Quaternion multiply(const Quaternion& q1, const Quaternion& q2) {
  const double s = q1.w() * q2.w() - q1.vec().dot(q2.vec());
  const Eigen::Vector3d v = q1.w() * q2.vec() + q2.w() * q1.vec() + q1.vec().cross(q2.vec());
  return Quaternion(s, v.x(), v.y(), v.z());
}

// Parent 4.3: q^-1 = (1/|q|^2) [s, -v].
// Computed as conj(q / m) / |q / m|^2 / m with m = max |q_i|, so that |q|^2 neither overflows
// (|q| > 1e154) nor underflows (|q| < 1e-154).
Quaternion inverse(const Quaternion& q) {
  const double m = q.coeffs().cwiseAbs().maxCoeff();
  if (!(m > 0.0) || !std::isfinite(m)) {  // contract violation: the plain formula (inf or NaN)
    const double n2 = q.squaredNorm();
    return Quaternion(q.w() / n2, -q.x() / n2, -q.y() / n2, -q.z() / n2);
  }
  const Eigen::Vector4d s = q.coeffs() / m;
  const double k = 1.0 / (s.squaredNorm() * m);
  return Quaternion(s.w() * k, -s.x() * k, -s.y() * k, -s.z() * k);
}

// Any non-zero multiple of q is the same rotation, so q is normalised first: q [0, v] q^-1 then
// stays finite for huge and tiny q alike.
Eigen::Vector3d rotate(const Quaternion& q_in, const Eigen::Vector3d& v) {
  const Quaternion q = normalised(q_in);
  const Quaternion p(0.0, v.x(), v.y(), v.z());
  return multiply(multiply(q, p), inverse(q)).vec();
}

bool sameRotation(const Quaternion& q1, const Quaternion& q2, double tol) {
  // On the unit quaternions (robustly normalised), so that huge and tiny ones compare too.
  const std::optional<Quaternion> a = vdg::normalizedOrNone(q1), b = vdg::normalizedOrNone(q2);
  if (!a || !b) return false;
  return std::abs(std::abs(a->coeffs().dot(b->coeffs())) - 1.0) <= tol;
}

double angleBetween(const Quaternion& q1, const Quaternion& q2) {
  const double d = std::abs(normalised(q1).coeffs().dot(normalised(q2).coeffs()));
  return 2.0 * std::acos(std::min(1.0, d));
}

Quaternion slerpGroupForm(const Quaternion& q1, const Quaternion& q2, double u) {
  const Quaternion a = normalised(q1), b = normalised(q2);
  // (q1^-1 q2)^u = exp(u log(q1^-1 q2)), log[cos h, sin h n] = [0, h n].
  const Quaternion d = multiply(inverse(a), b);
  const double vn = d.vec().norm();
  const double half = std::atan2(vn, d.w());
  const Eigen::Vector3d n = vn > 0.0 ? Eigen::Vector3d(d.vec() / vn) : Eigen::Vector3d::UnitX();
  const Eigen::Vector3d v = std::sin(u * half) * n;
  return multiply(a, Quaternion(std::cos(u * half), v.x(), v.y(), v.z()));
}

// Parent 4.3: slerp(q1, q2, u) = sin((1-u) th)/sin th q1 + sin(u th)/sin th q2, q1.q2 = cos th.
Quaternion slerp(const Quaternion& q1_in, const Quaternion& q2_in, double u) {
  const Quaternion q1 = normalised(q1_in);
  Quaternion q2 = normalised(q2_in);
  double c = q1.coeffs().dot(q2.coeffs());
  if (c < 0.0) {  // -q2 is the same rotation and lies on the shorter arc
    q2.coeffs() = -q2.coeffs();
    c = -c;
  }
  c = std::min(c, 1.0);
  const double th = std::acos(c);
  if (th < kSlerpLinearThreshold) return normalised(Quaternion((1 - u) * q1.coeffs() + u * q2.coeffs()));
  const double s = std::sin(th);
  Quaternion r(std::sin((1 - u) * th) / s * q1.coeffs() + std::sin(u * th) / s * q2.coeffs());
  return normalised(r);
}

Quaternion extend(const Quaternion& q1, const Quaternion& q2) {
  return normalised(multiply(multiply(q2, inverse(q1)), q2));
}

}  // namespace vdg::anim
