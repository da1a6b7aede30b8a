// Tracks — Parent, Computer Animation, sections 4.5 ("Simple Key Frame System") and 4.9 ("Key
// Frame and Track-Based Animation Systems": a track per parameter, keys as events on it,
// interpolation with ease-in/ease-out).
#include "vdg/anim/track.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

#include "vdg/geom/error.h"
#include "vdg/geom/normalize.h"

namespace vdg::anim {
namespace {

bool isRotationInterpolation(Interpolation i) {
  return i == Interpolation::kSlerp || i == Interpolation::kQuaternionCurve;
}

CurveKind curveKindOf(Interpolation i) {
  switch (i) {
    case Interpolation::kCatmullRom:
      return CurveKind::kCatmullRom;
    case Interpolation::kCentripetalCatmullRom:
      return CurveKind::kCentripetalCatmullRom;
    case Interpolation::kNaturalCubic:
      return CurveKind::kNaturalCubic;
    case Interpolation::kParabolicBlending:
      return CurveKind::kParabolicBlending;
    case Interpolation::kBezier:
      return CurveKind::kBezier;
    default:
      return CurveKind::kLinear;
  }
}

}  // namespace

const char* trackTypeName(TrackType type) {
  switch (type) {
    case TrackType::kScalar:
      return "scalar";
    case TrackType::kVector:
      return "vector";
    case TrackType::kRotation:
      return "rotation";
  }
  return "?";
}

const char* interpolationName(Interpolation interpolation) {
  switch (interpolation) {
    case Interpolation::kStep:
      return "step";
    case Interpolation::kLinear:
      return "linear";
    case Interpolation::kCatmullRom:
      return "catmull-rom";
    case Interpolation::kCentripetalCatmullRom:
      return "centripetal-catmull-rom";
    case Interpolation::kNaturalCubic:
      return "natural-cubic";
    case Interpolation::kParabolicBlending:
      return "parabolic-blending";
    case Interpolation::kBezier:
      return "bezier";
    case Interpolation::kSlerp:
      return "slerp";
    case Interpolation::kQuaternionCurve:
      return "quaternion-curve";
  }
  return "?";
}

const char* extrapolationName(Extrapolation extrapolation) {
  return extrapolation == Extrapolation::kLoop ? "loop" : "clamp";
}

void RawTrack::validate(const std::string& where) const {
  const std::string prefix = where + ": track '" + name + "': ";
  auto fail = [&](const std::string& what) { throw Error(prefix + what); };
  if (keys.empty()) fail("'keys': a track needs at least one key");
  const bool rotation = type == TrackType::kRotation;
  if (rotation && !isRotationInterpolation(interpolation) && interpolation != Interpolation::kStep) {
    fail(std::string("interpolation '") + interpolationName(interpolation) +
         "' is not available for rotation tracks (use 'slerp', 'quaternion-curve' or 'step')");
  }
  if (!rotation && isRotationInterpolation(interpolation)) {
    fail(std::string("interpolation '") + interpolationName(interpolation) + "' is only available for rotation tracks");
  }
  const auto expected = rotation ? 4 : type == TrackType::kScalar ? 1 : keys[0].value.size();
  for (std::size_t i = 0; i < keys.size(); ++i) {
    const RawKey& k = keys[i];
    std::ostringstream at;
    at << "'keys'[" << i << "]: ";
    if (!std::isfinite(k.time)) fail(at.str() + "'time' must be finite");
    if (i > 0 && !(k.time > keys[i - 1].time)) {
      std::ostringstream out;
      out << at.str() << "'time' " << k.time << " must be greater than the previous key's " << keys[i - 1].time;
      fail(out.str());
    }
    // Spans are divided by (segment parameters) and the whole range is the loop period.
    if (i > 0) {
      const double span = k.time - keys[i - 1].time, range = k.time - keys[0].time;
      std::ostringstream out;
      if (!isUsableTimeSpan(span)) {
        out << at.str() << "'time' " << k.time << ": the span from the previous key's " << keys[i - 1].time
            << (std::isinf(span) ? " overflows a double" : " is too small to divide by");
        fail(out.str());
      }
      if (!isUsableTimeSpan(range)) {
        out << at.str() << "'time' " << k.time << ": the span from the first key's " << keys[0].time
            << " overflows a double";
        fail(out.str());
      }
    }
    if (k.value.size() != expected || expected < 1) {
      std::ostringstream out;
      out << at.str() << "'value': expected " << expected << (expected == 1 ? " number" : " numbers")
          << (rotation ? " (quaternion w, x, y, z)" : "") << ", got " << k.value.size();
      fail(out.str());
    }
    if (expected > kMaxCurveDimension) {
      std::ostringstream out;
      out << at.str() << "'value': " << expected << " numbers; a track value may have at most " << kMaxCurveDimension;
      fail(out.str());
    }
    if (!k.value.allFinite()) fail(at.str() + "'value' must be finite");
    // Any finite non-zero length is a rotation (1e-200 too): a robust norm, not sum of squares.
    if (rotation && !(robustNorm(std::span<const double>(k.value.data(), 4)) > 0.0))
      fail(at.str() + "'value': a rotation quaternion must not be zero");
    for (const auto* handle : {&k.in_handle, &k.out_handle}) {
      if (!handle->has_value()) continue;
      const char* key_name = handle == &k.in_handle ? "'in'" : "'out'";
      if (interpolation != Interpolation::kBezier) {
        fail(at.str() + key_name + ": handles are only used by 'bezier' interpolation");
      }
      if ((*handle)->size() != expected || !(*handle)->allFinite()) {
        std::ostringstream out;
        out << at.str() << key_name << ": expected " << expected << " finite numbers, got " << (*handle)->size();
        fail(out.str());
      }
    }
  }
}

Track Track::build(const RawTrack& raw, const std::string& where) {
  raw.validate(where);
  Track t;
  t.name_ = raw.name;
  t.type_ = raw.type;
  t.interpolation_ = raw.interpolation;
  t.extrapolation_ = raw.extrapolation;
  const int n = static_cast<int>(raw.keys.size());
  const int dim = static_cast<int>(raw.keys[0].value.size());
  t.dimension_ = dim;
  for (int i = 0; i < n; ++i) {
    t.times_.push_back(raw.keys[i].time);
    if (i + 1 < n) t.eases_.push_back(raw.keys[i].ease.value_or(Ease::linear()));
  }
  if (raw.type == TrackType::kRotation) {
    std::vector<Quaternion> qs;
    for (int i = 0; i < n; ++i) {
      const Eigen::VectorXd& v = raw.keys[i].value;
      // Robust normalisation: a quaternion 1e200 long is still its rotation, not the identity.
      Quaternion q = normalizedOrNone(Quaternion(v[0], v[1], v[2], v[3])).value_or(Quaternion::Identity());
      if (i > 0 && qs.back().coeffs().dot(q.coeffs()) < 0.0) q.coeffs() = -q.coeffs();
      qs.push_back(q);
      t.values_.insert(t.values_.end(), {q.w(), q.x(), q.y(), q.z()});
    }
    if (n >= 2 && raw.interpolation == Interpolation::kQuaternionCurve) {
      t.quaternion_curve_ = QuaternionCurve::build(qs, t.times_, {}, where + ": track '" + raw.name + "'");
    }
    return t;
  }
  for (int i = 0; i < n; ++i) {
    for (int d = 0; d < dim; ++d) t.values_.push_back(raw.keys[i].value[d]);
  }
  if (n < 2 || raw.interpolation == Interpolation::kStep) return t;
  RawCurve rc;
  rc.kind = curveKindOf(raw.interpolation);
  rc.times = t.times_;
  if (rc.kind == CurveKind::kBezier) {
    // Missing handles sit on the Catmull-Rom tangent, a third of the segment away.
    std::vector<Eigen::VectorXd> m(n);
    for (int i = 0; i < n; ++i) {
      const int lo = std::max(i - 1, 0), hi = std::min(i + 1, n - 1);
      m[i] = (raw.keys[hi].value - raw.keys[lo].value) / (t.times_[hi] - t.times_[lo]);
    }
    for (int i = 0; i < n; ++i) {
      if (i > 0) {
        const double h = t.times_[i] - t.times_[i - 1];
        rc.points.push_back(raw.keys[i].in_handle.value_or(Eigen::VectorXd(raw.keys[i].value - m[i] * (h / 3))));
      }
      rc.points.push_back(raw.keys[i].value);
      if (i + 1 < n) {
        const double h = t.times_[i + 1] - t.times_[i];
        rc.points.push_back(raw.keys[i].out_handle.value_or(Eigen::VectorXd(raw.keys[i].value + m[i] * (h / 3))));
      }
    }
  } else {
    for (const RawKey& k : raw.keys) rc.points.push_back(k.value);
  }
  t.curve_ = Curve::build(rc, where + ": track '" + raw.name + "'");
  return t;
}

double Track::curveTime(double t) const {
  const double t0 = times_.front(), t1 = times_.back();
  const double period = t1 - t0;
  if (std::isnan(t)) t = t0;
  if (extrapolation_ == Extrapolation::kLoop && period > 0.0 && (t < t0 || t >= t1)) {
    double r = std::fmod(t - t0, period);
    if (!std::isfinite(r)) r = 0.0;  // t = +-inf (or t - t0 overflowing): no phase; the first key
    if (r < 0.0) r += period;
    t = t0 + r;
  }
  t = std::clamp(t, t0, t1);
  if (eases_.empty()) return t;
  const auto it = std::upper_bound(times_.begin(), times_.end(), t);
  const int s = std::clamp(static_cast<int>(it - times_.begin()) - 1, 0, static_cast<int>(eases_.size()) - 1);
  if (eases_[s].kind() == EaseKind::kLinear) return t;
  const double h = times_[s + 1] - times_[s];
  return times_[s] + eases_[s].evaluate((t - times_[s]) / h) * h;
}

bool Track::evaluate(double t, std::span<double> out) const {
  if (out.size() != static_cast<std::size_t>(dimension_) || !std::isfinite(t)) return false;
  const double ct = curveTime(t);
  const int n = keyCount();
  const auto key = [&](int i) { return values_.data() + static_cast<std::size_t>(i) * dimension_; };
  // Segment of ct (the last key counts as the end of the last segment).
  int s = 0;
  if (n > 1) {
    const auto it = std::upper_bound(times_.begin(), times_.end(), ct);
    s = std::clamp(static_cast<int>(it - times_.begin()) - 1, 0, n - 1);
  }
  if (n == 1 || interpolation_ == Interpolation::kStep) {
    std::copy(key(s), key(s) + dimension_, out.begin());
    return true;
  }
  if (type_ == TrackType::kRotation) {
    Quaternion q;
    if (quaternion_curve_) {
      if (!quaternion_curve_->evaluate(ct, q)) return false;
    } else {  // slerp between the two keys of the segment
      const int seg = std::min(s, n - 2);
      const double u = std::clamp((ct - times_[seg]) / (times_[seg + 1] - times_[seg]), 0.0, 1.0);
      const double* a = key(seg);
      const double* b = key(seg + 1);
      q = slerp(Quaternion(a[0], a[1], a[2], a[3]), Quaternion(b[0], b[1], b[2], b[3]), u);
    }
    out[0] = q.w();
    out[1] = q.x();
    out[2] = q.y();
    out[3] = q.z();
    return true;
  }
  return curve_->evaluate(ct, out);
}

namespace {
[[noreturn]] void throwBadTime(const std::string& name, double t) {
  throw Error("track '" + name + "': time " + std::to_string(t) + " is not finite");
}
}  // namespace

Eigen::VectorXd Track::at(double t) const {
  Eigen::VectorXd v(dimension_);
  if (!evaluate(t, std::span<double>(v.data(), static_cast<std::size_t>(dimension_)))) throwBadTime(name_, t);
  return v;
}

double Track::scalarAt(double t) const {
  if (dimension_ > 4) return at(t)[0];
  double v[4] = {0, 0, 0, 0};
  if (!evaluate(t, std::span<double>(v, static_cast<std::size_t>(dimension_)))) throwBadTime(name_, t);
  return v[0];
}

Quaternion Track::rotationAt(double t) const {
  if (type_ != TrackType::kRotation)
    throw Error("track '" + name_ + "': rotationAt on a " + trackTypeName(type_) + " track");
  double v[4] = {1, 0, 0, 0};
  if (!evaluate(t, std::span<double>(v, 4))) throwBadTime(name_, t);
  return Quaternion(v[0], v[1], v[2], v[3]);
}

}  // namespace vdg::anim
