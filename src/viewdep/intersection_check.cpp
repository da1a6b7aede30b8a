// Views at which a view-dependent model's blend passes through itself (vdg/viewdep/
// intersection_check.h). Blends: Rademacher 99, section 3.2.3 (static) and section 4 (animated).
#include "vdg/viewdep/intersection_check.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <iterator>
#include <numbers>
#include <string>

#include "vdg/geom/error.h"
#include "vdg/geom/parallel.h"
#include "vdg/geom/self_intersection.h"

namespace vdg {
namespace {

using Pairs = std::vector<std::pair<std::int32_t, std::int32_t>>;

struct Candidate {
  Eigen::Vector3d view;
  int key = -1;
};

// What the check needs of a model: its triangles, the base at a frame, the blend at (frame, view).
struct CheckInput {
  std::span<const std::int32_t> triangles;
  std::size_t floats = 0;  // #V x 3
  std::function<std::span<const float>(int frame)> base;
  std::function<bool(int frame, const Eigen::Vector3d& view, std::span<float> out)> blend;
  std::vector<Candidate> views;
  std::vector<int> frames;
  double tolerance = 0;
};

IntersectionReport run(const CheckInput& in) {
  const std::vector<std::int32_t> weld = weldByPosition(in.base(in.frames.front()));
  IntersectionReport report;
  const std::size_t per_frame = in.views.size();
  report.views_checked = per_frame * in.frames.size();
  std::vector<IntersectingView> results(report.views_checked);
  for (std::size_t f = 0; f < in.frames.size(); ++f) {
    const int frame = in.frames[f];
    const Pairs base_pairs = selfIntersections(in.base(frame), in.triangles, weld, in.tolerance);
    report.base_pairs += base_pairs.size();
    detail::parallelChunks(per_frame, 4, [&](std::size_t begin, std::size_t end) {
      std::vector<float> blended(in.floats);
      for (std::size_t v = begin; v < end; ++v) {
        IntersectingView& r = results[f * per_frame + v];
        r.view = in.views[v].view;
        r.key = in.views[v].key;
        r.frame = frame;
        if (!in.blend(frame, r.view, blended)) continue;
        const Pairs found = newIntersections(blended, in.triangles, weld, base_pairs, in.tolerance);
        r.new_pairs = found.size();
        if (!found.empty()) r.example = found.front();
      }
    });
  }
  for (const IntersectingView& r : results)
    if (r.new_pairs > 0) {
      if (report.worst < 0 || r.new_pairs > report.views[static_cast<std::size_t>(report.worst)].new_pairs)
        report.worst = static_cast<int>(report.views.size());
      report.views.push_back(r);
    }
  return report;
}

void checkSamples(const IntersectionCheckSettings& s) {
  if (s.samples < 0 || s.samples > kMaxIntersectionSamples)
    throw Error("intersection check: samples must be in 0.." + std::to_string(kMaxIntersectionSamples) + ", got " +
                std::to_string(s.samples));
}

std::vector<Candidate> candidates(const std::vector<Eigen::Vector3d>& keys, int samples) {
  std::vector<Candidate> out;
  for (std::size_t k = 0; k < keys.size(); ++k) out.push_back({keys[k].normalized(), static_cast<int>(k)});
  for (const Eigen::Vector3d& d : fibonacciDirections(samples)) out.push_back({d, -1});
  return out;
}

}  // namespace

std::vector<Eigen::Vector3d> fibonacciDirections(int n) {
  std::vector<Eigen::Vector3d> dirs;
  const double golden = std::numbers::pi * (3.0 - std::sqrt(5.0));
  for (int i = 0; i < n; ++i) {
    const double y = 1.0 - (i + 0.5) * 2.0 / n;
    const double r = std::sqrt(std::max(0.0, 1.0 - y * y));
    dirs.emplace_back(r * std::cos(golden * i), y, r * std::sin(golden * i));
  }
  return dirs;
}

Pairs newIntersections(std::span<const float> blended, std::span<const std::int32_t> triangles,
                       std::span<const std::int32_t> weld, const Pairs& base_pairs, double tolerance) {
  const Pairs found = selfIntersections(blended, triangles, weld, tolerance);
  Pairs fresh;
  std::set_difference(found.begin(), found.end(), base_pairs.begin(), base_pairs.end(), std::back_inserter(fresh));
  return fresh;
}

Pairs keyIntersections(const TriMesh& base, std::span<const float> key_positions) {
  const std::vector<std::int32_t> weld = weldByPosition(base.positions);
  const double tolerance = kIntersectionRelativeTolerance * 0.5 * computeBounds(base.positions).diagonal();
  const Pairs base_pairs = selfIntersections(base.positions, base.triangles, weld, tolerance);
  return newIntersections(key_positions, base.triangles, weld, base_pairs, tolerance);
}

IntersectionReport checkIntersections(const ViewDependentModel& model, const IntersectionCheckSettings& settings) {
  checkSamples(settings);
  CheckInput in;
  in.triangles = model.base().triangles;
  in.floats = 3 * model.vertexCount();
  in.base = [&](int) { return std::span<const float>(model.base().positions); };
  in.blend = [&](int, const Eigen::Vector3d& view, std::span<float> out) { return model.evaluate(view, 0.0, out); };
  std::vector<Eigen::Vector3d> keys;
  for (std::size_t k = 0; k < model.keyCount(); ++k) keys.push_back(model.keyView(k));
  in.views = candidates(keys, settings.samples);
  in.frames = {0};
  in.tolerance = kIntersectionRelativeTolerance * model.extentRadius();
  return run(in);
}

IntersectionReport checkIntersections(const AnimatedViewDependentModel& model,
                                      const IntersectionCheckSettings& settings) {
  checkSamples(settings);
  CheckInput in;
  in.frames = settings.frames.empty() ? std::vector<int>{0} : settings.frames;
  for (int f : in.frames)
    if (f < 0 || f >= model.frameCount())
      throw Error("intersection check: frame " + std::to_string(f) + " is outside 0.." +
                  std::to_string(model.frameCount() - 1));
  in.triangles = model.base().triangles;
  in.floats = 3 * model.vertexCount();
  in.base = [&](int frame) { return model.baseFrame(frame); };
  in.blend = [&](int frame, const Eigen::Vector3d& view, std::span<float> out) {
    return model.evaluate(frame, view, 0.0, out);
  };
  std::vector<Eigen::Vector3d> keys;
  for (std::size_t v = 0; v < model.viewCount(); ++v) keys.push_back(model.viewDirection(v));
  in.views = candidates(keys, settings.samples);
  in.tolerance = kIntersectionRelativeTolerance * model.extentRadius();
  return run(in);
}

}  // namespace vdg
