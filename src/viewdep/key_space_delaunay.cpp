// The key eyes' Delaunay tetrahedralisation (vdg/viewdep/key_space.h): the one translation unit of
// viewdep that includes CGAL (its templates are slow to compile). Exact predicates, inexact
// constructions: the triangulation's combinatorics are exact for any double input.
#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>

#include <map>
#include <utility>

#include "vdg/viewdep/key_space.h"

namespace vdg::detail {
namespace {
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using VertexBase = CGAL::Triangulation_vertex_base_with_info_3<int, Kernel>;
using Tds = CGAL::Triangulation_data_structure_3<VertexBase>;
using Delaunay = CGAL::Delaunay_triangulation_3<Kernel, Tds>;
}  // namespace

Tetrahedralisation delaunayTetrahedra(std::span<const Eigen::Vector3d> points) {
  std::vector<std::pair<Kernel::Point_3, int>> input;
  input.reserve(points.size());
  for (std::size_t i = 0; i < points.size(); ++i)
    input.emplace_back(Kernel::Point_3(points[i].x(), points[i].y(), points[i].z()), static_cast<int>(i));
  Delaunay dt(input.begin(), input.end());
  Tetrahedralisation out;
  if (dt.dimension() < 3) return out;
  std::map<Delaunay::Cell_handle, int> index;
  for (auto c = dt.finite_cells_begin(); c != dt.finite_cells_end(); ++c) {
    index.emplace(c, static_cast<int>(out.tets.size()));
    out.tets.push_back({c->vertex(0)->info(), c->vertex(1)->info(), c->vertex(2)->info(), c->vertex(3)->info()});
  }
  out.neighbours.resize(out.tets.size());
  for (auto c = dt.finite_cells_begin(); c != dt.finite_cells_end(); ++c) {
    const int t = index.at(c);
    for (int i = 0; i < 4; ++i) {
      const Delaunay::Cell_handle n = c->neighbor(i);
      out.neighbours[static_cast<std::size_t>(t)][static_cast<std::size_t>(i)] = dt.is_infinite(n) ? -1 : index.at(n);
    }
  }
  return out;
}

}  // namespace vdg::detail
