// Implicit surfaces: blobby objects, soft objects and metaballs (Parent 4.11; vdg/morph/implicit.h
// for the field functions and their sources): the fields, their animation and the grid's size. The
// polygoniser (OpenVDB) is polygonise.cpp, in vdg::morph3d.
#include "vdg/morph/implicit.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <sstream>
#include <string>

#include "vdg/geom/error.h"
#include "vdg/geom/text.h"
#include "vdg/morph/budget.h"

namespace vdg::morph {
namespace {

bool finite3(const Eigen::Vector3d& v) { return v.allFinite() && v.cwiseAbs().maxCoeff() <= kMaxBlobValue; }

// "" when v is in [lo, hi]; else what is wrong ("must be > 0, got -1", "must be in [...], got X").
std::string outside(double v, double lo, double hi) {
  if (v >= lo && v <= hi) return "";
  if (!(v > 0) && lo > 0) return "must be > 0, got " + numberText(v);
  return "must be in [" + numberText(lo) + ", " + numberText(hi) + "], got " + numberText(v);
}

// Blinn's a = B / R^2 (section comment of the header).
double blinnA(const BlobPrimitive& p) { return p.blobbiness / (p.radius * p.radius); }

}  // namespace

const char* fieldKindName(FieldKind kind) {
  switch (kind) {
    case FieldKind::kBlinn:
      return "blinn";
    case FieldKind::kWyvill:
      return "wyvill";
    case FieldKind::kNishimura:
      return "nishimura";
  }
  return "?";
}

double primitiveField(const BlobPrimitive& p, double r) {
  switch (p.kind) {
    case FieldKind::kBlinn:  // Blinn 1982: D(r) = b exp(-a r^2), a = B / R^2.
      return p.strength * std::exp(-blinnA(p) * r * r);
    case FieldKind::kWyvill: {  // Wyvill et al. 1986: C = 1 - 22/9 q + 17/9 q^2 - 4/9 q^3, q = r^2/R^2.
      if (r >= p.radius) return 0.0;
      const double q = (r * r) / (p.radius * p.radius);
      return p.strength * (1.0 + q * (-22.0 / 9.0 + q * (17.0 / 9.0 - q * (4.0 / 9.0))));
    }
    case FieldKind::kNishimura: {  // Nishimura et al. 1985: piecewise quadratic.
      if (r >= p.radius) return 0.0;
      if (r <= p.radius / 3.0) return p.strength * (1.0 - 3.0 * r * r / (p.radius * p.radius));
      const double u = 1.0 - r / p.radius;
      return 1.5 * p.strength * u * u;
    }
  }
  return 0.0;
}

double supportRadius(const BlobPrimitive& p, double threshold) {
  if (p.kind != FieldKind::kBlinn) return p.radius;
  // |b| exp(-a r^2) = |T| 1e-3  <=>  r^2 = ln(|b| / (|T| 1e-3)) / a.
  const double floor_value = std::abs(threshold) * kBlinnCutoff;
  if (!(std::abs(p.strength) > floor_value)) return 0.0;
  return std::sqrt(std::log(std::abs(p.strength) / floor_value) / blinnA(p));
}

// ---- BlobModel ------------------------------------------------------------------------------

void RawBlobModel::validate(const std::string& where) const {
  if (primitives.empty()) throw Error(where + ": no primitives");
  if (primitives.size() > kMaxBlobPrimitives)
    throw Error(where + ": " + std::to_string(primitives.size()) + " primitives; at most " +
                std::to_string(kMaxBlobPrimitives) + " are allowed");
  if (const std::string e = outside(threshold, kMinBlobValue, kMaxBlobValue); !e.empty())
    throw Error(where + ": threshold " + e);
  for (std::size_t i = 0; i < primitives.size(); ++i) {
    const BlobPrimitive& p = primitives[i];
    const std::string at = where + ": primitives[" + std::to_string(i) + "]: ";
    if (!finite3(p.center)) throw Error(at + "center must be 3 numbers in [-1e+12, 1e+12]");
    if (const std::string e = outside(p.radius, kMinBlobValue, kMaxBlobValue); !e.empty())
      throw Error(at + "radius " + e);
    if (const std::string e = outside(p.strength, -kMaxBlobValue, kMaxBlobValue); !e.empty())
      throw Error(at + "strength " + e);
    if (const std::string e = outside(p.blobbiness, kMinBlobbiness, kMaxBlobbiness); !e.empty())
      throw Error(at + "blobbiness " + e);
  }
}

BlobModel BlobModel::build(const RawBlobModel& raw, const std::string& where) {
  raw.validate(where);
  BlobModel m;
  m.primitives_ = raw.primitives;
  m.active_.assign(raw.primitives.size(), 1);
  m.threshold_ = raw.threshold;
  return m;
}

double BlobModel::field(const Eigen::Vector3d& p) const {
  double sum = 0;
  for (std::size_t i = 0; i < primitives_.size(); ++i)
    if (active_[i]) sum += primitiveField(primitives_[i], (p - primitives_[i].center).norm());
  return sum;
}

Eigen::Vector3d BlobModel::gradient(const Eigen::Vector3d& p) const {
  Eigen::Vector3d g = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < primitives_.size(); ++i) {
    if (!active_[i]) continue;
    const BlobPrimitive& b = primitives_[i];
    const Eigen::Vector3d d = p - b.center;
    const double r = d.norm();
    const double R2 = b.radius * b.radius;
    switch (b.kind) {
      case FieldKind::kBlinn:  // d/dp b exp(-a r^2) = -2 a d D(r)
        g += -2.0 * blinnA(b) * primitiveField(b, r) * d;
        break;
      case FieldKind::kWyvill: {  // dC/dq * dq/dp, dq/dp = 2 d / R^2
        if (r >= b.radius) break;
        const double q = r * r / R2;
        const double dcdq = -22.0 / 9.0 + q * (34.0 / 9.0 - q * (12.0 / 9.0));
        g += b.strength * dcdq * (2.0 / R2) * d;
        break;
      }
      case FieldKind::kNishimura:
        if (r >= b.radius) break;
        if (r <= b.radius / 3.0) {
          g += b.strength * (-6.0 / R2) * d;  // d/dp b (1 - 3 r^2 / R^2)
        } else {
          // d/dp 3b/2 (1 - r/R)^2 = -3b/R (1 - r/R) d / r
          g += (-3.0 * b.strength / b.radius) * (1.0 - r / b.radius) / r * d;
        }
        break;
    }
  }
  return g;
}

bool BlobModel::sample(std::span<const double> points, std::span<double> values) const {
  if (points.size() != 3 * values.size()) return false;
  for (double c : points)
    if (!std::isfinite(c)) return false;
  for (std::size_t i = 0; i < values.size(); ++i)
    values[i] = field(Eigen::Vector3d(points[3 * i], points[3 * i + 1], points[3 * i + 2]));
  return true;
}

Eigen::AlignedBox3d BlobModel::bounds() const {
  Eigen::AlignedBox3d box;  // empty
  for (std::size_t i = 0; i < primitives_.size(); ++i) {
    const BlobPrimitive& p = primitives_[i];
    if (!active_[i] || !(p.strength > 0)) continue;
    const double r = supportRadius(p, threshold_);
    if (!(r > 0)) continue;
    box.extend(p.center - Eigen::Vector3d::Constant(r));
    box.extend(p.center + Eigen::Vector3d::Constant(r));
  }
  return box;
}

// ---- Animation ------------------------------------------------------------------------------

void RawBlobAnimation::validate(const std::string& where) const {
  if (primitives.empty()) throw Error(where + ": no primitives");
  if (primitives.size() > kMaxBlobPrimitives)
    throw Error(where + ": " + std::to_string(primitives.size()) + " primitives; at most " +
                std::to_string(kMaxBlobPrimitives) + " are allowed");
  if (const std::string e = outside(threshold, kMinBlobValue, kMaxBlobValue); !e.empty())
    throw Error(where + ": threshold " + e);
  if (first_frame > last_frame)
    throw Error(where + ": frames: the first frame " + std::to_string(first_frame) + " is after the last " +
                std::to_string(last_frame));
  for (std::size_t i = 0; i < primitives.size(); ++i) {
    const RawBlobTrack& p = primitives[i];
    const std::string at = where + ": primitives[" + std::to_string(i) + "]";
    p.center.validate(at + ".'center'");
    p.radius.validate(at + ".'radius'");
    p.strength.validate(at + ".'strength'");
    const auto need = [&](const anim::RawTrack& t, const char* name, anim::TrackType type, long size) {
      if (t.type != type || t.keys.front().value.size() != size)
        throw Error(at + ".'" + name + "': expected a track of " + (size == 1 ? "numbers" : "3 numbers"));
    };
    need(p.center, "center", anim::TrackType::kVector, 3);
    need(p.radius, "radius", anim::TrackType::kScalar, 1);
    need(p.strength, "strength", anim::TrackType::kScalar, 1);
    if (const std::string e = outside(p.blobbiness, kMinBlobbiness, kMaxBlobbiness); !e.empty())
      throw Error(at + ": blobbiness " + e);
    for (std::size_t k = 0; k < p.radius.keys.size(); ++k)
      if (const std::string e = outside(p.radius.keys[k].value[0], kMinBlobValue, kMaxBlobValue); !e.empty())
        throw Error(at + ".'radius': key " + std::to_string(k) + ": radius " + e);
    for (std::size_t k = 0; k < p.strength.keys.size(); ++k)
      if (const std::string e = outside(p.strength.keys[k].value[0], -kMaxBlobValue, kMaxBlobValue); !e.empty())
        throw Error(at + ".'strength': key " + std::to_string(k) + ": strength " + e);
    for (std::size_t k = 0; k < p.center.keys.size(); ++k)
      if (!finite3(p.center.keys[k].value.head<3>()))
        throw Error(at + ".'center': key " + std::to_string(k) + ": center must be 3 numbers in [-1e+12, 1e+12]");
  }
}

BlobAnimation BlobAnimation::build(const RawBlobAnimation& raw, const std::string& where) {
  raw.validate(where);
  BlobAnimation a;
  for (std::size_t i = 0; i < raw.primitives.size(); ++i) {
    const RawBlobTrack& p = raw.primitives[i];
    const std::string at = where + ": primitives[" + std::to_string(i) + "]";
    a.kinds_.push_back(p.kind);
    a.blobbiness_.push_back(p.blobbiness);
    a.centers_.push_back(anim::Track::build(p.center, at + ".'center'"));
    a.radii_.push_back(anim::Track::build(p.radius, at + ".'radius'"));
    a.strengths_.push_back(anim::Track::build(p.strength, at + ".'strength'"));
  }
  a.threshold_ = raw.threshold;
  a.first_frame_ = raw.first_frame;
  a.last_frame_ = raw.last_frame;
  return a;
}

BlobModel BlobAnimation::modelAt(double frame) const {
  if (!std::isfinite(frame)) throw Error("blob animation: frame " + numberText(frame) + " is not finite");
  BlobModel m;
  m.threshold_ = threshold_;
  m.primitives_.resize(kinds_.size());
  m.active_.assign(kinds_.size(), 1);
  if (!evaluate(frame, m)) throw Error("blob animation: cannot evaluate frame " + numberText(frame));
  return m;
}

bool BlobAnimation::evaluate(double frame, BlobModel& model) const {
  if (!std::isfinite(frame) || model.primitives_.size() != kinds_.size() || model.active_.size() != kinds_.size())
    return false;
  for (std::size_t i = 0; i < kinds_.size(); ++i) {
    BlobPrimitive& p = model.primitives_[i];
    double c[3], r = 0, s = 0;
    // The tracks were built with these sizes, so evaluation cannot fail here.
    const bool ok = centers_[i].evaluate(frame, c) && radii_[i].evaluate(frame, std::span<double>(&r, 1)) &&
                    strengths_[i].evaluate(frame, std::span<double>(&s, 1));
    p.kind = kinds_[i];
    p.blobbiness = blobbiness_[i];
    p.center = Eigen::Vector3d(c[0], c[1], c[2]);
    p.strength = s;
    // An overshooting interpolation may take the radius to 0 or below: the primitive is off.
    const bool on =
        ok && r > 0 && std::isfinite(r) && (kinds_[i] != FieldKind::kBlinn || std::isfinite(p.blobbiness / (r * r)));
    p.radius = on ? r : 1.0;
    model.active_[i] = on ? 1 : 0;
  }
  model.threshold_ = threshold_;
  return true;
}

// ---- Polygonisation -------------------------------------------------------------------------

double defaultVoxelSize(const Eigen::AlignedBox3d& box) {
  if (box.isEmpty()) return 0.0;
  return box.sizes().maxCoeff() / 96.0;
}

Eigen::Vector3d gridDimensions(const Eigen::AlignedBox3d& box, double h) {
  Eigen::Vector3d n;
  for (int a = 0; a < 3; ++a) n[a] = std::ceil(box.sizes()[a] / h) + 1.0 + 2.0 * kGridPadding;
  return n;
}

double gridVoxelCount(const Eigen::AlignedBox3d& box, double voxel_size) {
  if (box.isEmpty()) return 0.0;
  return gridDimensions(box, voxel_size).prod();
}

void checkVoxelBudget(const Eigen::AlignedBox3d& box, double h, std::size_t max_voxels, const std::string& what) {
  const double count = gridVoxelCount(box, h);
  if (count <= static_cast<double>(max_voxels)) return;
  // The smallest voxel size (3 significant digits, rounded up) whose grid fits.
  double s = h * std::cbrt(count / static_cast<double>(max_voxels));
  for (int tries = 0; tries < 200 && gridVoxelCount(box, s) > static_cast<double>(max_voxels); ++tries) s *= 1.01;
  if (std::isfinite(s) && s > 0) {
    const double scale = std::pow(10.0, std::floor(std::log10(s)) - 2.0);
    s = std::ceil(s / scale) * scale;
  }
  // A count past what a double holds (a voxel of 1e-300) or a guess that overflowed: search instead.
  if (!std::isfinite(count) || !std::isfinite(s) || !(s > 0) ||
      gridVoxelCount(box, s) > static_cast<double>(max_voxels))
    s = smallestFittingSize([&](double size) { return gridVoxelCount(box, size); }, h, static_cast<double>(max_voxels));
  const double mib = count * static_cast<double>(kBytesPerVoxel) / (1024.0 * 1024.0);
  std::ostringstream msg;
  msg.precision(6);
  // Whole numbers below 1e15 (exact in a double), else 3 significant digits ("8e+18").
  const auto amount = [](double v) {
    std::ostringstream t;
    if (!std::isfinite(v)) {
      t << "more than 1e308";
    } else if (v < 1e15) {
      t << std::llround(v);
    } else {
      t.precision(3);
      t << v;
    }
    return t.str();
  };
  msg << what << ": the grid needs " << amount(count) << " voxels"
      << (std::isfinite(count) ? " (about " + amount(mib) + " MiB)" : std::string()) << " at voxel size " << h
      << "; use a --voxel of at least " << s;
  throw Error(msg.str());
}

std::size_t connectedComponents(const TriMesh& mesh) {
  const std::size_t n = mesh.vertexCount();
  std::vector<std::size_t> parent(n);
  std::iota(parent.begin(), parent.end(), std::size_t{0});
  const auto find = [&](std::size_t v) {
    while (parent[v] != v) v = parent[v] = parent[parent[v]];
    return v;
  };
  std::vector<char> used(n, 0);
  for (std::size_t f = 0; f < mesh.triangleCount(); ++f) {
    const auto a = static_cast<std::size_t>(mesh.triangles[3 * f]);
    for (int k = 0; k < 3; ++k) {
      const auto b = static_cast<std::size_t>(mesh.triangles[3 * f + k]);
      used[b] = 1;
      parent[find(a)] = find(b);
    }
  }
  std::size_t components = 0;
  for (std::size_t v = 0; v < n; ++v)
    if (used[v] && find(v) == v) ++components;
  return components;
}

}  // namespace vdg::morph
