// Two-pass mesh warp and mesh morph — Parent, Computer Animation, section 4.10 ("Shape
// Interpolation, Metamorphosis"), after Smythe's two-pass mesh warping (D. B. Smythe, "A Two-Pass
// Mesh Warping Algorithm for Object Transformation and Image Interpolation", ILM memo 1030, 1990).
//
// The user places the same number of grid intersection points on the source and the destination;
// Catmull-Rom curves through the columns and rows of points make a curvilinear grid. The warp
// moves what lies under grid `from` to grid `to` in two one-dimensional passes:
//
//   Pass 1 (x): source image -> intermediate image, along each scanline. The column curves of the
//   source grid and of the intermediate grid cross the scanline at x-intercepts; each curve's
//   index c and its intercept give the pairs (c, x_c), through which a Catmull-Rom spline is
//   passed. A source pixel's boundaries are located in the source's (index, x) spline as
//   fractional indices, and those indices are located in the intermediate's spline as x positions:
//   the source pixel covers that span of the intermediate scanline. Each intermediate pixel takes
//   the colours of the source pixels over it weighted by the fraction of it they cover (a box
//   filter: the colour integral along the scanline is carried over, and edges are anti-aliased).
//   Pass 2 (y): intermediate image -> output, the same along each column of pixels, with the row
//   curves of the intermediate grid and of `to`.
//
// The intermediate grid. Parent's text says the intermediate grid point takes "the x-coordinate of
// the source grid point and the y-coordinate of the destination grid point", but its figure shows
// the source control points "shoved horizontally to a position directly underneath the control
// points of the destination grid", and only that works: pass 1 moves pixels along x only, so every
// point keeps its y and can at best reach the destination's x; pass 2 moves along y only, so it
// must start from points that already have the destination's x. Hence here
//     intermediate(r, c) = (x of to(r, c), y of from(r, c)).
// With it, pass 1 takes a feature at from(r, c) = (xs, ys) to (xd, ys) (both grids' column curve c
// pass through height ys, at xs and xd), and pass 2 takes (xd, ys) to (xd, yd) = to(r, c) (both
// grids' row curve r pass through x = xd, at ys and yd). With the text's literal choice (xs, yd)
// pass 1 would have to move points vertically, which a horizontal pass cannot do.
//
// Choices the text leaves open, made here:
// - A column curve is parameterised by y (x = X_c(y), the non-uniform Catmull-Rom through
//   (y_r, x_r), tangents as in the anim module's kCatmullRom), a row curve by x. validateGrid
//   demands strictly increasing y down a column and x along a row, so each curve crosses every
//   scanline (resp. pixel column) exactly once and the intercept is one evaluation.
// - Above the first and below the last grid row a column curve continues vertically (its end x),
//   likewise row curves horizontally beyond the first and last column: the outermost cells are
//   extended straight out to the image border, and curves that are in order at the end points stay
//   in order there. Should curves of a wild grid still cross between control points, the intercepts
//   on that scanline are put back in order (each at least 1e-6 pixel right of the previous one).
// - The (index, intercept) spline is the uniform Catmull-Rom spline in the index (tangent
//   (x_{c+1} - x_{c-1}) / 2, the chord at the ends, as the phantom points P_{-1} = 2 P_0 - P_1 give)
//   with each tangent limited to 3 times the smaller adjacent chord (Fritsch and Carlson's
//   condition), so that it increases monotonically and a pixel boundary has exactly one fractional
//   index. The limit changes nothing unless neighbouring cells differ in width more than about
//   five-fold. Beyond the first and last curve the spline continues linearly with the end chord
//   slope (the outermost cell extended, C1 at the end curve).
// - Source pixels beyond the image border (needed where the warp pulls content in from outside)
//   repeat the border pixel, so every output pixel is fully covered.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

#include "morph_2d_internal.h"
#include "vdg/anim/curve.h"
#include "vdg/geom/error.h"
#include "vdg/geom/parallel.h"
#include "vdg/geom/text.h"
#include "vdg/morph/image_morph.h"

namespace vdg::morph {
namespace {

using Eigen::Vector2d;

// Curves through the grid, each x = X(t) over strictly increasing knots t (non-uniform Catmull-Rom
// in Hermite form; Parent 4.1 / vdg/anim/curve.h kCatmullRom), constant beyond the end knots.
struct KnotCurves {
  int count = 0, knots = 0;
  std::vector<double> t, v, m;  // count * knots each

  void build() {
    m.assign(t.size(), 0.0);
    for (int c = 0; c < count; ++c) {
      const double* tc = &t[static_cast<std::size_t>(c) * knots];
      const double* vc = &v[static_cast<std::size_t>(c) * knots];
      double* mc = &m[static_cast<std::size_t>(c) * knots];
      for (int k = 0; k < knots; ++k) {
        const int a = std::max(k - 1, 0), b = std::min(k + 1, knots - 1);
        mc[k] = (vc[b] - vc[a]) / (tc[b] - tc[a]);  // interior: (P_{k+1} - P_{k-1}) / (t_{k+1} - t_{k-1}); ends: chord
      }
    }
  }
  double eval(int c, double at) const {
    const double* tc = &t[static_cast<std::size_t>(c) * knots];
    const double* vc = &v[static_cast<std::size_t>(c) * knots];
    const double* mc = &m[static_cast<std::size_t>(c) * knots];
    if (at <= tc[0]) return vc[0];
    if (at >= tc[knots - 1]) return vc[knots - 1];
    const int k = static_cast<int>(std::upper_bound(tc, tc + knots, at) - tc) - 1;
    const double h = tc[k + 1] - tc[k], u = (at - tc[k]) / h;
    const double u2 = u * u, u3 = u2 * u;
    return (2 * u3 - 3 * u2 + 1) * vc[k] + (u3 - 2 * u2 + u) * h * mc[k] + (-2 * u3 + 3 * u2) * vc[k + 1] +
           (u3 - u2) * h * mc[k + 1];
  }
};

// Column curves (x as a function of y, one per grid column) or row curves (y as a function of x,
// one per grid row).
KnotCurves gridCurves(const WarpGrid& g, bool columns) {
  KnotCurves curves;
  curves.count = columns ? g.cols : g.rows;
  curves.knots = columns ? g.rows : g.cols;
  curves.t.resize(static_cast<std::size_t>(curves.count) * curves.knots);
  curves.v.resize(curves.t.size());
  for (int c = 0; c < curves.count; ++c)
    for (int k = 0; k < curves.knots; ++k) {
      const Vector2d& p = columns ? g.at(k, c) : g.at(c, k);
      const std::size_t i = static_cast<std::size_t>(c) * curves.knots + k;
      curves.t[i] = columns ? p.y() : p.x();
      curves.v[i] = columns ? p.x() : p.y();
    }
  curves.build();
  return curves;
}

// The (index, intercept) spline of one scanline: x = S(s) with S(c) = x_c, monotone (see the top).
class IndexSpline {
 public:
  static constexpr double kFar = 1e9;
  // x: n >= 2 intercepts, put in strictly increasing order here.
  void build(std::vector<double>& x) {
    const int n = static_cast<int>(x.size());
    // Intercepts far outside any image are clamped (1e9 px keeps a 1e-6 px step representable) and
    // put in strictly increasing order (curves of a wild grid may cross between control points).
    for (int c = 0; c < n; ++c) x[c] = x[c] > -kFar ? std::min(x[c], kFar) : -kFar;
    for (int c = 1; c < n; ++c)
      if (!(x[c] > x[c - 1])) x[c] = x[c - 1] + 1e-6;
    x_ = x;
    m_.assign(x.size(), 0.0);
    for (int c = 0; c < n; ++c) {
      const int a = std::max(c - 1, 0), b = std::min(c + 1, n - 1);
      double tangent = (x[b] - x[a]) / (b - a);  // Catmull-Rom (x_{c+1} - x_{c-1}) / 2; chord at the ends
      if (c > 0) tangent = std::min(tangent, 3 * (x[c] - x[c - 1]));  // Fritsch-Carlson: monotone
      if (c + 1 < n) tangent = std::min(tangent, 3 * (x[c + 1] - x[c]));
      m_[c] = tangent;
    }
  }
  double value(double s) const {
    const int n = static_cast<int>(x_.size());
    if (!(s > 0)) return x_[0] + s * (x_[1] - x_[0]);  // (NaN too: no cast below)
    if (s >= n - 1) return x_[n - 1] + (s - (n - 1)) * (x_[n - 1] - x_[n - 2]);
    const int k = std::min(static_cast<int>(s), n - 2);
    return hermite(k, s - k);
  }
  // The s with value(s) = x.
  double inverse(double x) const {
    const int n = static_cast<int>(x_.size());
    if (x <= x_[0]) return (x - x_[0]) / (x_[1] - x_[0]);
    if (x >= x_[n - 1]) return (n - 1) + (x - x_[n - 1]) / (x_[n - 1] - x_[n - 2]);
    const int k = std::clamp(static_cast<int>(std::upper_bound(x_.begin(), x_.end(), x) - x_.begin()) - 1, 0, n - 2);
    // Safeguarded Newton on the monotone cubic of segment k, bracketed in [lo, hi].
    double lo = 0, hi = 1;
    double u = (x - x_[k]) / (x_[k + 1] - x_[k]);
    const double tolerance = 1e-12 * std::max(1.0, std::abs(x));
    for (int iteration = 0; iteration < 60; ++iteration) {
      const double f = hermite(k, u) - x;
      if (std::abs(f) <= tolerance) break;
      (f < 0 ? lo : hi) = u;
      const double d = derivative(k, u);
      double next = d > 0 ? u - f / d : 0.5 * (lo + hi);
      if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
      if (next == u) break;
      u = next;
    }
    return k + u;
  }

 private:
  double hermite(int k, double u) const {
    const double u2 = u * u, u3 = u2 * u;
    return (2 * u3 - 3 * u2 + 1) * x_[k] + (u3 - 2 * u2 + u) * m_[k] + (-2 * u3 + 3 * u2) * x_[k + 1] +
           (u3 - u2) * m_[k + 1];
  }
  double derivative(int k, double u) const {
    const double u2 = u * u;
    return (6 * u2 - 6 * u) * x_[k] + (3 * u2 - 4 * u + 1) * m_[k] + (-6 * u2 + 6 * u) * x_[k + 1] +
           (3 * u2 - 2 * u) * m_[k + 1];
  }
  std::vector<double> x_, m_;
};

// Per-thread scratch of one pass.
struct LineScratch {
  std::vector<double> from_x, to_x;  // intercepts
  IndexSpline from, to;
  std::vector<float> in, out;      // one line of pixels, 4 floats each
  std::vector<double> sum, cover;  // per output pixel: sum of colour x coverage, total coverage
};

// Adds colour `c` over [a, b) of the output line (clipped to [0, n)) with fractional coverage.
void deposit(double a, double b, const float* c, LineScratch& s, int n) {
  a = std::max(a, 0.0);
  b = std::min(b, static_cast<double>(n));
  if (!(b > a)) return;
  const int first = static_cast<int>(a);
  const int last = std::min(static_cast<int>(std::ceil(b)), n);  // exclusive
  for (int j = first; j < last; ++j) {
    const double overlap = std::min(b, j + 1.0) - std::max(a, static_cast<double>(j));
    if (!(overlap > 0)) continue;
    for (int k = 0; k < 4; ++k) s.sum[static_cast<std::size_t>(j) * 4 + k] += overlap * c[k];
    s.cover[static_cast<std::size_t>(j)] += overlap;
  }
}

// Parent 4.10, one pass along a line of n pixels: source pixel i covers [i, i+1); its boundaries
// are located as fractional indices in the `from` spline and mapped to positions in the `to`
// spline; output pixel j gets the coverage-weighted average of what lands on [j, j+1).
void resampleLine(LineScratch& s, int n) {
  s.sum.assign(static_cast<std::size_t>(n) * 4, 0.0);
  s.cover.assign(static_cast<std::size_t>(n), 0.0);
  const float* in = s.in.data();
  auto mapped = [&](double x) { return s.to.value(s.from.inverse(x)); };
  double left = mapped(0.0);
  deposit(-1.0, left, in, s, n);  // beyond the left border: the border pixel repeated
  for (int i = 0; i < n && left < n; ++i) {
    const double right = mapped(i + 1.0);
    deposit(left, right, in + static_cast<std::size_t>(i) * 4, s, n);
    left = right;
  }
  deposit(left, n + 1.0, in + static_cast<std::size_t>(n - 1) * 4, s, n);  // beyond the right border
  for (int j = 0; j < n; ++j) {
    const double cover = s.cover[static_cast<std::size_t>(j)];
    for (int k = 0; k < 4; ++k) {
      const std::size_t i = static_cast<std::size_t>(j) * 4 + k;
      s.out[i] = cover > 0 ? static_cast<float>(s.sum[i] / cover) : 0.0f;
    }
  }
}

// One pass: horizontal (lines are scanlines, curves the grid's columns) or vertical (lines are
// pixel columns, curves the grid's rows).
Image warpPass(const Image& image, const WarpGrid& from, const WarpGrid& to, bool horizontal) {
  const KnotCurves from_curves = gridCurves(from, horizontal);
  const KnotCurves to_curves = gridCurves(to, horizontal);
  Image out{.width = image.width, .height = image.height, .rgba = std::vector<float>(image.rgba.size())};
  const int lines = horizontal ? image.height : image.width;
  const int length = horizontal ? image.width : image.height;
  vdg::detail::parallelChunks(static_cast<std::size_t>(lines), 16, [&](std::size_t begin, std::size_t end) {
    LineScratch s;
    s.from_x.resize(static_cast<std::size_t>(from_curves.count));
    s.to_x.resize(static_cast<std::size_t>(to_curves.count));
    s.in.resize(static_cast<std::size_t>(length) * 4);
    s.out.resize(s.in.size());
    for (std::size_t line = begin; line < end; ++line) {
      const int l = static_cast<int>(line);
      const double across = l + 0.5;  // the scanline through the pixel centres
      for (int c = 0; c < from_curves.count; ++c) {
        s.from_x[static_cast<std::size_t>(c)] = from_curves.eval(c, across);
        s.to_x[static_cast<std::size_t>(c)] = to_curves.eval(c, across);
      }
      s.from.build(s.from_x);
      s.to.build(s.to_x);
      for (int i = 0; i < length; ++i) {
        const float* p = horizontal ? image.pixel(i, l) : image.pixel(l, i);
        std::copy(p, p + 4, s.in.begin() + static_cast<std::ptrdiff_t>(i) * 4);
      }
      resampleLine(s, length);
      for (int i = 0; i < length; ++i) {
        float* p = horizontal ? out.pixel(i, l) : out.pixel(l, i);
        std::copy(s.out.begin() + static_cast<std::ptrdiff_t>(i) * 4,
                  s.out.begin() + static_cast<std::ptrdiff_t>(i) * 4 + 4, p);
      }
    }
  });
  return out;
}

}  // namespace

WarpGrid identityGrid(int rows, int cols, int width, int height) {
  if (rows < 2 || cols < 2)
    throw Error("identity grid: " + std::to_string(rows) + " x " + std::to_string(cols) +
                " points; a grid needs at least 2 x 2");
  if (width < 1 || height < 1)
    throw Error("identity grid: the image size " + std::to_string(width) + " x " + std::to_string(height) +
                " needs at least 1 x 1 pixels");
  WarpGrid g{.rows = rows, .cols = cols, .points = std::vector<Vector2d>(static_cast<std::size_t>(rows) * cols)};
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c)
      g.at(r, c) = Vector2d(static_cast<double>(width) * c / (cols - 1), static_cast<double>(height) * r / (rows - 1));
  return g;
}

void validateGrid(const WarpGrid& grid, const std::string& what) {
  if (grid.rows < 2 || grid.cols < 2)
    throw Error(what + ": the grid is " + std::to_string(grid.rows) + " x " + std::to_string(grid.cols) +
                " points; it needs at least 2 x 2");
  const std::size_t expected = static_cast<std::size_t>(grid.rows) * static_cast<std::size_t>(grid.cols);
  if (grid.points.size() != expected)
    throw Error(what + ": a " + std::to_string(grid.rows) + " x " + std::to_string(grid.cols) + " grid needs " +
                std::to_string(expected) + " points but has " + std::to_string(grid.points.size()));
  for (int r = 0; r < grid.rows; ++r)
    for (int c = 0; c < grid.cols; ++c) {
      const Vector2d& p = grid.at(r, c);
      const std::string where = what + ": the point at row " + std::to_string(r) + ", column " + std::to_string(c);
      if (!p.allFinite()) throw Error(where + " is not finite");
      if (p.cwiseAbs().maxCoeff() > kMaxMorphCoordinate)
        throw Error(where + " (" + numberText(p.x(), 10) + ", " + numberText(p.y(), 10) + ") is farther than " +
                    numberText(kMaxMorphCoordinate, 10) + " pixels from the origin in x or y");
    }
  for (int r = 0; r < grid.rows; ++r)
    for (int c = 0; c + 1 < grid.cols; ++c)
      if (!(grid.at(r, c + 1).x() - grid.at(r, c).x() >= kMinGridSpacing))
        throw Error(what + ": row " + std::to_string(r) + ": the point at column " + std::to_string(c + 1) +
                    " (x = " + numberText(grid.at(r, c + 1).x(), 10) + ") is not right of column " + std::to_string(c) +
                    " (x = " + numberText(grid.at(r, c).x(), 10) +
                    "); grid lines must not cross or touch (x increases along a row by at least " +
                    numberText(kMinGridSpacing, 10) + ")");
  for (int c = 0; c < grid.cols; ++c)
    for (int r = 0; r + 1 < grid.rows; ++r)
      if (!(grid.at(r + 1, c).y() - grid.at(r, c).y() >= kMinGridSpacing))
        throw Error(what + ": column " + std::to_string(c) + ": the point at row " + std::to_string(r + 1) +
                    " (y = " + numberText(grid.at(r + 1, c).y(), 10) + ") is not below row " + std::to_string(r) +
                    " (y = " + numberText(grid.at(r, c).y(), 10) +
                    "); grid lines must not cross or touch (y increases down a column by at least " +
                    numberText(kMinGridSpacing, 10) + ")");
}

void requireSameShape(const WarpGrid& a, const WarpGrid& b, const std::string& what) {
  if (a.rows != b.rows || a.cols != b.cols)
    throw Error(what + ": the grids differ in shape (" + std::to_string(a.rows) + " x " + std::to_string(a.cols) +
                " and " + std::to_string(b.rows) + " x " + std::to_string(b.cols) + " points)");
}

WarpGrid interpolateGrids(const WarpGrid& a, const WarpGrid& b, double t) {
  requireSameShape(a, b, "interpolate grids");
  if (a.points.size() != b.points.size())
    throw Error("interpolate grids: the grids hold " + std::to_string(a.points.size()) + " and " +
                std::to_string(b.points.size()) + " points");
  if (!std::isfinite(t)) throw Error("interpolate grids: t is not finite");
  // Parent 4.10: "the grid vertices ... are interpolated to form an intermediate grid" (linearly).
  // Exact at t = 0 and t = 1: (1 - t) a + t b with one factor 0 and the other 1.
  WarpGrid g{.rows = a.rows, .cols = a.cols, .points = std::vector<Vector2d>(a.points.size())};
  for (std::size_t i = 0; i < a.points.size(); ++i) g.points[i] = (1 - t) * a.points[i] + t * b.points[i];
  return g;
}

WarpGrid gridAtTime(std::span<const GridKey> keys, double time) {
  if (keys.empty()) throw Error("grid keys: none given (at least one is needed)");
  if (!std::isfinite(time)) throw Error("grid keys: time " + numberText(time, 10) + " is not finite");
  std::vector<double> times;
  for (std::size_t k = 0; k < keys.size(); ++k) {
    const std::string where = "grid key " + std::to_string(k);
    if (!std::isfinite(keys[k].time)) throw Error(where + ": the time is not finite");
    if (k > 0 && !(keys[k].time > keys[k - 1].time))
      throw Error(where + ": time " + numberText(keys[k].time, 10) + " is not after key " + std::to_string(k - 1) +
                  "'s time " + numberText(keys[k - 1].time, 10) + " (key times must increase strictly)");
    if (k > 0 && !anim::isUsableTimeSpan(keys[k].time - keys[k - 1].time))
      throw Error(where + ": the span from key " + std::to_string(k - 1) + "'s time " +
                  numberText(keys[k - 1].time, 10) + " to " + numberText(keys[k].time, 10) +
                  " is too small or too large");
    validateGrid(keys[k].grid, where);
    requireSameShape(keys.front().grid, keys[k].grid, where);
    times.push_back(keys[k].time);
  }
  // Parent 4.10, animated morphs: "The coordinate grids are then interpolated over time ...
  // Catmull-Rom interpolation can be used." Every coordinate over the key times; exact at keys.
  const detail::KeyWeights w = detail::keyWeights(times, time, true);
  const WarpGrid& first = keys[static_cast<std::size_t>(w.index[0])].grid;
  WarpGrid g{.rows = first.rows, .cols = first.cols, .points = std::vector<Vector2d>(first.points.size())};
  for (std::size_t i = 0; i < g.points.size(); ++i) {
    Vector2d p = w.weight[0] * first.points[i];
    for (int k = 1; k < w.count; ++k) p += w.weight[k] * keys[static_cast<std::size_t>(w.index[k])].grid.points[i];
    g.points[i] = p;
  }
  return g;
}

Image meshWarp(const Image& image, const WarpGrid& from, const WarpGrid& to) {
  validateImage(image, "mesh warp: image");
  validateGrid(from, "mesh warp: source grid");
  validateGrid(to, "mesh warp: destination grid");
  requireSameShape(from, to, "mesh warp");
  if (from.points == to.points) return image;  // nothing moves: the image itself, bit for bit
  // The intermediate grid: x of the destination, y of the source (see the top of this file).
  WarpGrid middle = from;
  for (std::size_t i = 0; i < middle.points.size(); ++i) middle.points[i].x() = to.points[i].x();
  const Image first = warpPass(image, from, middle, true);  // pass 1: along x, column curves
  return warpPass(first, middle, to, false);                // pass 2: along y, row curves
}

Image meshMorph(const Image& src, const Image& dst, const WarpGrid& src_grid, const WarpGrid& dst_grid, double t) {
  validateImage(src, "mesh morph: source image");
  validateImage(dst, "mesh morph: destination image");
  if (src.width != dst.width || src.height != dst.height)
    throw Error("mesh morph: the images differ in size (" + std::to_string(src.width) + " x " +
                std::to_string(src.height) + " and " + std::to_string(dst.width) + " x " + std::to_string(dst.height) +
                ")");
  validateGrid(src_grid, "mesh morph: source grid");
  validateGrid(dst_grid, "mesh morph: destination grid");
  requireSameShape(src_grid, dst_grid, "mesh morph");
  if (!std::isfinite(t)) throw Error("mesh morph: t is not finite");
  // Parent 4.10: both images warped onto the inbetween grid, then cross-dissolved pixel by pixel.
  // An image whose dissolve weight is 0 is not warped (t = 0 gives src, t = 1 dst, exactly).
  const WarpGrid middle = interpolateGrids(src_grid, dst_grid, t);
  if (t == 0) return src;
  if (t == 1) return dst;
  return crossDissolve(meshWarp(src, src_grid, middle), meshWarp(dst, dst_grid, middle), t);
}

double meshWarpCost(int width, int height, int rows, int cols) {
  const double w = std::max(width, 0), h = std::max(height, 0), r = std::max(rows, 2), c = std::max(cols, 2);
  return 2 * (w * h * (std::log2(std::max(r, c)) + 1) + (w + h) * r * c);
}

double meshMorphCost(int width, int height, int rows, int cols) {
  return 2 * meshWarpCost(width, height, rows, cols) + static_cast<double>(std::max(width, 0)) * std::max(height, 0);
}

}  // namespace vdg::morph
