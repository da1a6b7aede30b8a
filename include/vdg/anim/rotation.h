// Orientation representations and interpolation (Parent, Computer Animation, section 4.3).
//
// Conventions (ours, which differ from the text's): column vectors, points are PRE-multiplied
// (p' = R p), right-handed, angles in radians. The text uses row vectors post-multiplied by the
// matrices (p' = p R), so its product Rx(a) Ry(b) Rz(c) ("first x, then y, then z") is our
// Rz(c) Ry(b) Rx(a), and its quaternion rotation q^-1 v q is our q v q^-1. 4x4 matrices hold the
// rotation in the upper-left 3x3 block and the translation in the fourth column (the text: fourth
// row). Quaternions are Eigen::Quaterniond, stored (x, y, z, w); constructed as Quaterniond(w, x, y, z).
//
// Angle triples:
//   fixed angles x-y-z (alpha, beta, gamma): rotate about world x by alpha, then world y by beta,
//     then world z by gamma: R = Rz(gamma) Ry(beta) Rx(alpha).
//   Euler angles z-y-x (gamma, beta, alpha): rotate about the body's z by gamma, then the rotated
//     y' by beta, then the twice-rotated x'' by alpha: the same matrix Rz(gamma) Ry(beta) Rx(alpha)
//     (Parent 4.3: "z-y-x Euler angles are equivalent to x-y-z fixed angles").
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace vdg::anim {

using Quaternion = Eigen::Quaterniond;

// Elementary rotations (radians).
Eigen::Matrix3d rotationX(double angle);
Eigen::Matrix3d rotationY(double angle);
Eigen::Matrix3d rotationZ(double angle);

// Fixed angles x-y-z, `xyz` = (alpha, beta, gamma): R = Rz(gamma) Ry(beta) Rx(alpha).
Eigen::Matrix3d fixedAnglesToMatrix(const Eigen::Vector3d& xyz);
// Inverse of fixedAnglesToMatrix for a rotation matrix: beta in [-pi/2, pi/2], alpha and gamma in
// (-pi, pi]. At gimbal lock (|beta| = pi/2) only alpha -/+ gamma is defined; gamma = 0 is returned.
Eigen::Vector3d matrixToFixedAngles(const Eigen::Matrix3d& r);
// Euler angles z-y-x, `zyx` = (gamma, beta, alpha): R = Rz(gamma) Ry'(beta) Rx''(alpha).
Eigen::Matrix3d eulerZyxToMatrix(const Eigen::Vector3d& zyx);
Eigen::Vector3d matrixToEulerZyx(const Eigen::Matrix3d& r);

// 3x3 <-> 4x4 (translation in the fourth column; bottom row 0 0 0 1).
Eigen::Matrix4d toMatrix4(const Eigen::Matrix3d& rotation,
                          const Eigen::Vector3d& translation = Eigen::Vector3d::Zero());
Eigen::Matrix3d rotationPart(const Eigen::Matrix4d& m);
Eigen::Vector3d translationPart(const Eigen::Matrix4d& m);

// Axis-angle: Parent 4.3 q = Rot(axis, theta) = [cos(theta/2), sin(theta/2) axis]. `axis` is
// normalised (robustly: any finite length); a zero or non-finite axis gives the identity.
Quaternion axisAngleToQuaternion(const Eigen::Vector3d& axis, double angle);
// Unit axis and angle in [0, pi] (axis (1,0,0) for the identity). q is normalised first.
void quaternionToAxisAngle(const Quaternion& q, Eigen::Vector3d* axis, double* angle);

Quaternion matrixToQuaternion(const Eigen::Matrix3d& r);  // unit, w >= 0
Eigen::Matrix3d quaternionToMatrix(const Quaternion& q);  // q normalised first
Quaternion fixedAnglesToQuaternion(const Eigen::Vector3d& xyz);
Eigen::Vector3d quaternionToFixedAngles(const Quaternion& q);

// Parent 4.3: [s1,v1][s2,v2] = [s1 s2 - v1.v2, s1 v2 + s2 v1 + v1 x v2].
Quaternion multiply(const Quaternion& q1, const Quaternion& q2);
// Parent 4.3: q^-1 = (1 / |q|^2) [s, -v], computed with q scaled by its largest component so
// that |q|^2 neither overflows nor underflows. q must be non-zero and finite.
Quaternion inverse(const Quaternion& q);
// Rotation of v by q: q [0, v] q^-1 (the text's q^-1 v q in its row-vector convention). Any
// finite non-zero multiple of q gives the same result (q is normalised robustly first: 1e200 q
// is q's rotation, not the identity); a zero or non-finite q rotates by the identity.
Eigen::Vector3d rotate(const Quaternion& q, const Eigen::Vector3d& v);
// q and k q (k != 0, in particular -q) are the same rotation: | |u1.u2| - 1 | <= tol for the unit
// quaternions u = q / |q| (robustly normalised, any finite magnitude). False when either is zero
// or not finite.
bool sameRotation(const Quaternion& q1, const Quaternion& q2, double tol = 1e-9);
// Angle in [0, pi] of the rotation taking q1 to q2.
double angleBetween(const Quaternion& q1, const Quaternion& q2);
// q1 (q1^-1 q2)^u for unit quaternions via the logarithm: the text's group form of slerp
// (no shortest-arc sign flip; used to check slerp()).
Quaternion slerpGroupForm(const Quaternion& q1, const Quaternion& q2, double u);

// Parent 4.3 spherical linear interpolation, 4D form:
// slerp(q1, q2, u) = sin((1-u) th)/sin(th) q1 + sin(u th)/sin(th) q2, cos(th) = q1.q2, along the
// SHORTEST arc (q2 is negated when q1.q2 < 0, since -q2 is the same rotation). Inputs are
// normalised; the result is unit. u = 1/2 gives normalise(q1 + q2). Near th = 0 falls back to
// normalised linear interpolation. u is not clamped (extrapolates along the great circle).
Quaternion slerp(const Quaternion& q1, const Quaternion& q2, double u);

// Rotation ("vector") concatenation used by the quaternion curve: the orientation reached from q2
// by applying again the rotation that takes q1 to q2: q2 q1^-1 q2 (Shoemake's Double(q1, q2)).
Quaternion extend(const Quaternion& q1, const Quaternion& q2);

}  // namespace vdg::anim
