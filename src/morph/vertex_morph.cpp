#include "vdg/morph/vertex_morph.h"

#include <cmath>

#include "vdg/geom/error.h"
#include "vdg/geom/text.h"

namespace vdg::morph {

VertexMorph::VertexMorph(std::vector<float> on_a, std::vector<float> on_b, std::vector<std::int32_t> triangles,
                         std::string name)
    : pos_a_(std::move(on_a)), pos_b_(std::move(on_b)), triangles_(std::move(triangles)), name_(std::move(name)) {
  if (pos_a_.size() != pos_b_.size() || pos_a_.size() % 3 != 0 || triangles_.size() % 3 != 0)
    throw Error(name_ + ": the placements on A and B must be #V x 3 each and the triangles #F x 3");
  const auto vertices = static_cast<std::int64_t>(pos_a_.size() / 3);
  for (const std::int32_t v : triangles_)
    if (v < 0 || v >= vertices)
      throw Error(name_ + ": a triangle names vertex " + std::to_string(v) + " of " + std::to_string(vertices));
}

bool VertexMorph::evaluate(double t, std::span<float> positions) const {
  if (!std::isfinite(t) || positions.size() != pos_a_.size()) return false;
  const double s = 1.0 - t;
  for (std::size_t i = 0; i < pos_a_.size(); ++i)
    positions[i] = static_cast<float>(s * static_cast<double>(pos_a_[i]) + t * static_cast<double>(pos_b_[i]));
  return true;
}

TriMesh VertexMorph::at(double t) const {
  TriMesh m;
  m.positions.resize(pos_a_.size());
  if (!evaluate(t, m.positions)) throw Error(name_ + ": t " + numberText(t, 6) + " is not a finite number");
  m.triangles = triangles_;
  return m;
}

}  // namespace vdg::morph
