// No vertex through the mesh (the paper's future work, Rademacher 99 section 6): the views (and
// frames) at which a view-dependent model's blend intersects itself where its base does not.
// vdg info --check-intersections and the studio's warning after a stroke use it
// (docs/where-to-key.md).
//
// Views checked: the key views themselves, then `samples` directions spread evenly over the
// sphere (a Fibonacci lattice, fibonacciDirections()). At each view (and frame of an animated
// model) the blend (section 3.2.3; section 4 at a frame) is evaluated and its intersecting
// triangle pairs found (vdg/geom/self_intersection.h: a uniform grid and Moller's test, vertices
// shared by position); the base's own pairs at the same frame are subtracted, so a base that
// already passes through itself is not reported. Threaded over views (vdg/geom/parallel.h).
#pragma once

#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "vdg/viewdep/animated_model.h"
#include "vdg/viewdep/model.h"

namespace vdg {

inline constexpr int kMaxIntersectionSamples = 100'000;

struct IntersectionCheckSettings {
  int samples = 200;        // sphere directions besides the key views, in [0, kMaxIntersectionSamples]
  std::vector<int> frames;  // animated models: frames to check (empty: frame 0); static: ignored
};

struct IntersectingView {
  Eigen::Vector3d view = Eigen::Vector3d::UnitZ();  // unit, towards the eye
  int frame = 0;
  int key = -1;  // the key view (key index of a static model, view index of an animated one) or -1
  std::size_t new_pairs = 0;
  std::pair<std::int32_t, std::int32_t> example{-1, -1};  // the first new pair (triangle indices)
};

struct IntersectionReport {
  std::size_t views_checked = 0;        // views x frames
  std::size_t base_pairs = 0;           // the base's own intersecting pairs, summed over the frames checked
  std::vector<IntersectingView> views;  // only those with new pairs, in the order checked
  int worst = -1;                       // index into views of the most new pairs (-1: none)
};

// n unit directions spread evenly over the sphere (Fibonacci lattice, y from +1 to -1).
std::vector<Eigen::Vector3d> fibonacciDirections(int n);

// New intersecting pairs of `blended` (#V x 3) not in the sorted `base_pairs`, for `triangles`
// with `weld` (vdg/geom/self_intersection.h).
std::vector<std::pair<std::int32_t, std::int32_t>> newIntersections(
    std::span<const float> blended, std::span<const std::int32_t> triangles, std::span<const std::int32_t> weld,
    const std::vector<std::pair<std::int32_t, std::int32_t>>& base_pairs, double tolerance);

// A key at its own view (weight 1: the blend is the key mesh): its intersecting pairs that the base
// does not have. `base` supplies the triangles and the base positions; key_positions is #V x 3.
// What the studio checks after a stroke.
std::vector<std::pair<std::int32_t, std::int32_t>> keyIntersections(const TriMesh& base,
                                                                    std::span<const float> key_positions);

// Throws vdg::Error for samples outside [0, kMaxIntersectionSamples] or a frame outside the model's.
IntersectionReport checkIntersections(const ViewDependentModel& model, const IntersectionCheckSettings& settings = {});
IntersectionReport checkIntersections(const AnimatedViewDependentModel& model,
                                      const IntersectionCheckSettings& settings = {});

}  // namespace vdg
