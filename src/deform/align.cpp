// Camera alignment from 2D-3D correspondences (Rademacher 99, section 3.1.1 and its future work).
// DLT and its decomposition: Hartley and Zisserman, "Multiple View Geometry", 2nd ed., sections 4.4
// (normalisation), 6.1 (DLT), 6.3.1 (affine camera) and 6.2.4 (RQ decomposition); refinement by
// Levenberg-Marquardt (Marquardt 1963, with the diagonal scaling of J^T J).
#include "vdg/deform/align.h"

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <Eigen/QR>
#include <Eigen/SVD>
#include <cmath>
#include <functional>
#include <numbers>
#include <string>

#include "vdg/geom/error.h"

namespace vdg {

namespace {

constexpr int kMinPairs = 6;
constexpr double kDegenerate = 1e-7;  // relative singular value under which points are flat

// The parameters a vdg::Camera can hold, in the form the refinement works in.
struct Params {
  Eigen::Matrix3d R;     // world -> camera rows: right, -up, forward (x right, y down, z depth)
  Eigen::Vector3d eye;   // perspective: eye; parallel: (right . eye, up . eye, unused)
  double log_scale = 0;  // perspective: log focal length (px); parallel: log pixels per world unit
};

Eigen::Matrix3d rodrigues(const Eigen::Vector3d& w) {
  const double angle = w.norm();
  if (angle == 0) return Eigen::Matrix3d::Identity();
  return Eigen::AngleAxisd(angle, w / angle).toRotationMatrix();
}

Eigen::Vector2d projectParams(const Params& p, bool ortho, int width, int height, const Eigen::Vector3d& X) {
  const double s = std::exp(p.log_scale);
  if (ortho) {
    const double x = p.R.row(0).dot(X) - p.eye.x();
    const double y = p.R.row(1).dot(X) + p.eye.y();  // row 1 is -up
    return {0.5 * width + s * x, 0.5 * height + s * y};
  }
  const Eigen::Vector3d c = p.R * (X - p.eye);
  return {0.5 * width + s * c.x() / c.z(), 0.5 * height + s * c.y() / c.z()};
}

// Apply an increment: [eye or in-plane (3 or 2), rotation (3), log scale (1)].
Params stepParams(const Params& p, bool ortho, const Eigen::VectorXd& d) {
  Params q = p;
  q.R = p.R * rodrigues(d.segment<3>(0));
  if (ortho) {
    q.eye.x() += d[3];
    q.eye.y() += d[4];
    q.log_scale += d[5];
  } else {
    q.eye += d.segment<3>(3);
    q.log_scale += d[6];
  }
  return q;
}

Eigen::VectorXd residuals(const Params& p, bool ortho, int width, int height, std::span<const Eigen::Vector3d> X,
                          std::span<const Eigen::Vector2d> x) {
  Eigen::VectorXd r(2 * static_cast<Eigen::Index>(X.size()));
  for (std::size_t k = 0; k < X.size(); ++k)
    r.segment<2>(2 * static_cast<Eigen::Index>(k)) = projectParams(p, ortho, width, height, X[k]) - x[k];
  return r;
}

Params levenbergMarquardt(Params p, bool ortho, int width, int height, std::span<const Eigen::Vector3d> X,
                          std::span<const Eigen::Vector2d> x, int max_iterations, int& iterations) {
  const int n = ortho ? 6 : 7;
  Eigen::VectorXd r = residuals(p, ortho, width, height, X, x);
  double cost = r.squaredNorm();
  double lambda = 1e-3;
  iterations = 0;
  // Step sizes for the central-difference Jacobian: rotation in radians, eye in world units.
  double world_scale = 0;
  for (const auto& v : X) world_scale = std::max(world_scale, (v - X[0]).norm());
  for (int it = 0; it < max_iterations; ++it) {
    iterations = it + 1;
    Eigen::MatrixXd J(r.size(), n);
    for (int j = 0; j < n; ++j) {
      const bool is_eye = j >= 3 && j < (ortho ? 5 : 6);
      const double h = is_eye ? 1e-6 * std::max(world_scale, 1e-9) : 1e-6;
      Eigen::VectorXd d = Eigen::VectorXd::Zero(n);
      d[j] = h;
      const Eigen::VectorXd rp = residuals(stepParams(p, ortho, d), ortho, width, height, X, x);
      d[j] = -h;
      const Eigen::VectorXd rm = residuals(stepParams(p, ortho, d), ortho, width, height, X, x);
      J.col(j) = (rp - rm) / (2 * h);
    }
    const Eigen::MatrixXd JtJ = J.transpose() * J;
    const Eigen::VectorXd g = J.transpose() * r;
    bool improved = false;
    for (int attempt = 0; attempt < 20 && !improved; ++attempt) {
      Eigen::MatrixXd A = JtJ;
      for (int j = 0; j < n; ++j) A(j, j) += lambda * std::max(JtJ(j, j), 1e-12);
      const Eigen::VectorXd d = A.ldlt().solve(-g);
      const Params q = stepParams(p, ortho, d);
      const Eigen::VectorXd rq = residuals(q, ortho, width, height, X, x);
      const double cq = rq.squaredNorm();
      if (std::isfinite(cq) && cq < cost) {
        const double gain = cost - cq;
        p = q;
        r = rq;
        lambda = std::max(lambda / 10, 1e-12);
        improved = true;
        if (gain <= 1e-15 * cost || d.norm() < 1e-14) return p;
        cost = cq;
      } else {
        lambda *= 10;
      }
    }
    if (!improved) break;  // at a minimum to working precision
  }
  return p;
}

Camera toCamera(const Params& p, bool ortho, int height, const Eigen::Vector3d& centroid, double radius) {
  const Eigen::Vector3d right = p.R.row(0).transpose(), up = -p.R.row(1).transpose(), forward = p.R.row(2).transpose();
  Camera c;
  c.up = up;
  if (ortho) {
    const double back_offset = -forward.dot(centroid) + 2 * radius + 1;
    c.eye = right * p.eye.x() + up * p.eye.y() - forward * back_offset;
    c.target = c.eye + forward * (2 * radius + 1);
    c.ortho_height = height / std::exp(p.log_scale);
    c.fov_deg = 0;
  } else {
    c.eye = p.eye;
    const double depth = (centroid - p.eye).dot(forward);
    c.target = c.eye + forward * (depth > 0 ? depth : 1.0);
    c.fov_deg = 2.0 * std::atan(0.5 * height / std::exp(p.log_scale)) * 180.0 / std::numbers::pi;
  }
  return c;
}

// Hartley normalisation: translate to the centroid, scale the mean distance to sqrt(dim).
template <int D>
Eigen::Matrix<double, D + 1, D + 1> normalising(const std::vector<Eigen::Matrix<double, D, 1>>& pts) {
  Eigen::Matrix<double, D, 1> c = Eigen::Matrix<double, D, 1>::Zero();
  for (const auto& q : pts) c += q;
  c /= static_cast<double>(pts.size());
  double mean = 0;
  for (const auto& q : pts) mean += (q - c).norm();
  mean /= static_cast<double>(pts.size());
  const double s = std::sqrt(static_cast<double>(D)) / mean;
  Eigen::Matrix<double, D + 1, D + 1> T = Eigen::Matrix<double, D + 1, D + 1>::Identity() * s;
  T(D, D) = 1;
  T.template block<D, 1>(0, D) = -s * c;
  return T;
}

}  // namespace

std::vector<double> reprojectionErrors(const Camera& camera, std::span<const Eigen::Vector3d> points,
                                       std::span<const Eigen::Vector2d> pixels, int width, int height) {
  std::vector<double> e(points.size());
  for (std::size_t k = 0; k < points.size(); ++k)
    e[k] = (project(camera, width, height, points[k]).pixel - pixels[k]).norm();
  return e;
}

namespace {

// The starting projective camera: the DLT in normalised coordinates (T3, T2), decomposed into
// intrinsics and pose. Throws vdg::Error when it has no solution or the points are behind it.
Params projectiveStart(const std::vector<Eigen::Vector3d>& X, const std::vector<Eigen::Vector2d>& x,
                       const Eigen::Matrix4d& T3, const Eigen::Matrix3d& T2) {
  const std::size_t n = X.size();
  // DLT for the 3x4 projective camera (H&Z 7.1 / 6.1).
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(2 * static_cast<Eigen::Index>(n), 12);
  for (std::size_t k = 0; k < n; ++k) {
    const Eigen::Vector4d Xh = T3 * X[k].homogeneous();
    const Eigen::Vector3d xh = T2 * x[k].homogeneous();
    const auto r = 2 * static_cast<Eigen::Index>(k);
    A.block<1, 4>(r, 0) = Xh.transpose();
    A.block<1, 4>(r, 8) = -xh.x() * Xh.transpose();
    A.block<1, 4>(r + 1, 4) = Xh.transpose();
    A.block<1, 4>(r + 1, 8) = -xh.y() * Xh.transpose();
  }
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(A, Eigen::ComputeFullV);
  const Eigen::VectorXd h = svd.matrixV().col(11);
  Eigen::Matrix<double, 3, 4> Pn;
  Pn << h.segment<4>(0).transpose(), h.segment<4>(4).transpose(), h.segment<4>(8).transpose();
  Eigen::Matrix<double, 3, 4> P = T2.inverse() * Pn * T3;
  Eigen::Matrix3d M = P.leftCols<3>();
  if (M.determinant() < 0) {
    P = -P;
    M = -M;
  }
  if (!(std::abs(M.determinant()) > 0)) throw Error("align: degenerate correspondences: the DLT has no solution");
  // Cheirality: the points must be in front (H&Z 6.2.3).
  int behind = 0;
  for (const auto& p : X) behind += (P * p.homogeneous()).z() <= 0;
  if (2 * behind > static_cast<int>(n)) throw Error("align: the solved camera has the points behind it");
  // RQ of M = K R via QR of (J M)^T, J the row reversal.
  Eigen::Matrix3d J = Eigen::Matrix3d::Zero();
  J(0, 2) = J(1, 1) = J(2, 0) = 1;
  Eigen::HouseholderQR<Eigen::Matrix3d> qr((J * M).transpose());
  const Eigen::Matrix3d Q = qr.householderQ();
  const Eigen::Matrix3d U = qr.matrixQR().triangularView<Eigen::Upper>();
  Eigen::Matrix3d K = J * U.transpose() * J;
  Eigen::Matrix3d R = J * Q.transpose();
  for (int i = 0; i < 3; ++i)
    if (K(i, i) < 0) {
      K.col(i) *= -1;
      R.row(i) *= -1;
    }
  if (R.determinant() < 0) R = -R;  // numerically impossible with det M > 0; keep R proper anyway
  K /= K(2, 2);
  Params p0;
  p0.R = R;
  p0.eye = -M.inverse() * P.col(3);
  p0.log_scale = std::log(0.5 * (K(0, 0) + K(1, 1)));
  return p0;
}

// The starting parallel camera: an affine fit made orthonormal. Throws vdg::Error when the pixels
// do not spread.
Params affineStart(const std::vector<Eigen::Vector3d>& X, const std::vector<Eigen::Vector2d>& x,
                   const Eigen::Matrix4d& T3, int width, int height) {
  const std::size_t n = X.size();
  // Affine camera (H&Z 7.3): two independent linear least-squares fits of u and v.
  Eigen::MatrixXd A(static_cast<Eigen::Index>(n), 4);
  Eigen::MatrixXd b(static_cast<Eigen::Index>(n), 2);
  for (std::size_t k = 0; k < n; ++k) {
    const auto r = static_cast<Eigen::Index>(k);
    A.row(r) << (T3 * X[k].homogeneous()).transpose();
    b.row(r) = x[k].transpose();
  }
  const Eigen::Matrix<double, 4, 2> sol = A.colPivHouseholderQr().solve(b);
  const Eigen::Matrix<double, 2, 4> Pa = sol.transpose() * T3;
  const Eigen::Matrix<double, 2, 3> Ma = Pa.leftCols<3>();
  // Nearest scaled orthonormal rows (polar decomposition).
  Eigen::JacobiSVD<Eigen::Matrix<double, 2, 3>> svd(Ma, Eigen::ComputeFullU | Eigen::ComputeFullV);
  const Eigen::Matrix<double, 2, 3> rows = svd.matrixU() * svd.matrixV().leftCols<2>().transpose();
  const double s = 0.5 * (svd.singularValues()[0] + svd.singularValues()[1]);
  if (!(s > 0)) throw Error("align: degenerate correspondences: the pixels do not spread");
  Params p0;
  p0.R.row(0) = rows.row(0);
  p0.R.row(1) = rows.row(1);
  p0.R.row(2) = rows.row(0).cross(rows.row(1));
  p0.log_scale = std::log(s);
  p0.eye = Eigen::Vector3d((0.5 * width - Pa(0, 3)) / s, -(0.5 * height - Pa(1, 3)) / s, 0);
  return p0;
}

}  // namespace

AlignResult alignCamera(std::span<const Eigen::Vector3d> points, std::span<const Eigen::Vector2d> pixels, int width,
                        int height, const AlignOptions& options) {
  if (points.size() != pixels.size())
    throw Error("align: " + std::to_string(points.size()) + " points but " + std::to_string(pixels.size()) + " pixels");
  if (points.size() < kMinPairs)
    throw Error("align: need at least " + std::to_string(kMinPairs) + " point pairs, got " +
                std::to_string(points.size()));
  if (width <= 0 || height <= 0) throw Error("align: the image size must be positive");
  for (std::size_t k = 0; k < points.size(); ++k)
    if (!points[k].allFinite() || !pixels[k].allFinite())
      throw Error("align: pair " + std::to_string(k) + " has a non-finite coordinate");

  const std::size_t n = points.size();
  std::vector<Eigen::Vector3d> X(points.begin(), points.end());
  std::vector<Eigen::Vector2d> x(pixels.begin(), pixels.end());
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (const auto& p : X) centroid += p;
  centroid /= static_cast<double>(n);
  double radius = 0;
  Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
  for (const auto& p : X) {
    scatter += (p - centroid) * (p - centroid).transpose();
    radius = std::max(radius, (p - centroid).norm());
  }
  const Eigen::Vector3d sv = Eigen::JacobiSVD<Eigen::Matrix3d>(scatter).singularValues();  // variances
  if (!(sv[0] > 0) || sv[1] < kDegenerate * sv[0])
    throw Error("align: degenerate correspondences: all 3D points are collinear (or the same point)");
  if (sv[2] < kDegenerate * sv[0])
    throw Error(
        "align: degenerate correspondences: all 3D points are coplanar; the camera needs points off one "
        "plane (add pairs on another part of the model)");

  const Eigen::Matrix4d T3 = normalising<3>(X);
  const Eigen::Matrix3d T2 = normalising<2>(x);
  const Params p0 = options.ortho ? affineStart(X, x, T3, width, height) : projectiveStart(X, x, T3, T2);

  AlignResult result;
  {
    const Camera c0 = toCamera(p0, options.ortho, height, centroid, radius);
    double sum = 0;
    for (double e : reprojectionErrors(c0, X, x, width, height)) sum += e * e;
    result.dlt_rms_px = std::sqrt(sum / static_cast<double>(n));
  }
  const Params p =
      levenbergMarquardt(p0, options.ortho, width, height, X, x, options.max_iterations, result.iterations);
  result.camera = toCamera(p, options.ortho, height, centroid, radius);
  double sum = 0;
  for (double e : reprojectionErrors(result.camera, X, x, width, height)) {
    sum += e * e;
    result.max_px = std::max(result.max_px, e);
  }
  result.rms_px = std::sqrt(sum / static_cast<double>(n));
  if (!options.ortho)
    for (const auto& q : X)
      if (project(result.camera, width, height, q).depth <= 0)
        throw Error("align: the solved camera has some of the points behind it");
  return result;
}

}  // namespace vdg
