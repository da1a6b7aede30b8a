// Distances over a mesh for attenuated deformation (Parent, Computer Animation, 4.10).
// Geodesics by the heat method: Crane, Weischedel, Wardetzky, "Geodesics in Heat: A New Approach to
// Computing Distance Based on Heat Flow", ACM TOG 2013, algorithm 1 with the cotangent Laplacian.
#include "vdg/deform/distance.h"

#include <Eigen/Geometry>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <algorithm>
#include <cmath>
#include <queue>

#include "vdg/geom/error.h"
#include "vdg/geom/surface.h"

namespace vdg {

DistanceMetric parseDistanceMetric(const std::string& name, const std::string& what) {
  if (name == "euclidean") return DistanceMetric::kEuclidean;
  if (name == "edges") return DistanceMetric::kEdges;
  if (name == "geodesic") return DistanceMetric::kGeodesic;
  throw Error(what + ": unknown distance '" + name + "' (expected euclidean, edges or geodesic)");
}

const char* distanceMetricName(DistanceMetric metric) {
  switch (metric) {
    case DistanceMetric::kEuclidean:
      return "euclidean";
    case DistanceMetric::kEdges:
      return "edges";
    case DistanceMetric::kGeodesic:
      return "geodesic";
  }
  return "?";
}

namespace {
Eigen::Vector3d vertexAt(std::span<const float> positions, std::int64_t v) {
  return {positions[3 * v], positions[3 * v + 1], positions[3 * v + 2]};
}

// Vertex adjacency lists (each undirected edge once per endpoint).
std::vector<std::vector<std::int32_t>> adjacency(std::span<const std::int32_t> triangles, std::size_t n) {
  std::vector<std::vector<std::int32_t>> adj(n);
  for (std::size_t f = 0; f + 2 < triangles.size(); f += 3) {
    for (int c = 0; c < 3; ++c) {
      const std::int32_t a = triangles[f + c], b = triangles[f + (c + 1) % 3];
      adj[a].push_back(b);
      adj[b].push_back(a);
    }
  }
  for (auto& list : adj) {
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
  }
  return adj;
}
}  // namespace

void euclideanDistances(std::span<const float> positions, std::int32_t seed, std::span<double> out) {
  const Eigen::Vector3d s = vertexAt(positions, seed);
  for (std::size_t v = 0; v < out.size(); ++v) out[v] = (vertexAt(positions, static_cast<std::int64_t>(v)) - s).norm();
}

void edgeDistances(std::span<const std::int32_t> triangles, std::size_t vertex_count, std::int32_t seed,
                   std::span<double> out) {
  const auto adj = adjacency(triangles, vertex_count);
  std::fill(out.begin(), out.end(), kUnreachable);
  std::queue<std::int32_t> queue;
  out[seed] = 0;
  queue.push(seed);
  while (!queue.empty()) {
    const std::int32_t v = queue.front();
    queue.pop();
    for (std::int32_t w : adj[v]) {
      if (out[w] == kUnreachable) {
        out[w] = out[v] + 1;
        queue.push(w);
      }
    }
  }
}

struct GeodesicSolver::Impl {
  std::size_t n = 0;
  std::vector<Eigen::Vector3d> pos;
  std::vector<std::int32_t> tris;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> heat;    // M + t L (Neumann boundary)
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> heat_d;  // the same, u = 0 on the boundary
  bool has_boundary = false;
  std::vector<char> boundary;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> poisson;  // L + eps M
  std::vector<std::vector<std::int32_t>> adj;                  // for reachability
};

GeodesicSolver::GeodesicSolver(std::span<const float> positions, std::span<const std::int32_t> triangles)
    : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  m.n = positions.size() / 3;
  if (triangles.size() < 3) throw Error("geodesic distance: the mesh has no triangles");
  m.pos.resize(m.n);
  for (std::size_t v = 0; v < m.n; ++v) m.pos[v] = vertexAt(positions, static_cast<std::int64_t>(v));
  m.tris.assign(triangles.begin(), triangles.end());
  m.adj = adjacency(triangles, m.n);

  // Cotangent Laplacian L (positive semi-definite: L_ij = -(cot a + cot b)/2) and lumped mass M.
  std::vector<Eigen::Triplet<double>> lt;
  Eigen::VectorXd mass = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(m.n));
  double edge_sum = 0;
  std::size_t edge_count = 0;
  for (std::size_t f = 0; f + 2 < m.tris.size(); f += 3) {
    const std::int32_t idx[3] = {m.tris[f], m.tris[f + 1], m.tris[f + 2]};
    const double area = 0.5 * (m.pos[idx[1]] - m.pos[idx[0]]).cross(m.pos[idx[2]] - m.pos[idx[0]]).norm();
    if (!(area > 0)) continue;
    for (int c = 0; c < 3; ++c) {
      const std::int32_t i = idx[c], j = idx[(c + 1) % 3], k = idx[(c + 2) % 3];
      // Angle at k, opposite edge (i, j).
      const Eigen::Vector3d a = m.pos[i] - m.pos[k], b = m.pos[j] - m.pos[k];
      const double cot = a.dot(b) / a.cross(b).norm();
      const double w = 0.5 * cot;
      lt.emplace_back(i, j, -w);
      lt.emplace_back(j, i, -w);
      lt.emplace_back(i, i, w);
      lt.emplace_back(j, j, w);
      mass[i] += area / 3.0;
      edge_sum += (m.pos[i] - m.pos[j]).norm();
      ++edge_count;
    }
  }
  if (edge_count == 0) throw Error("geodesic distance: every triangle of the mesh is degenerate");
  const auto n = static_cast<Eigen::Index>(m.n);
  Eigen::SparseMatrix<double> L(n, n), M(n, n);
  L.setFromTriplets(lt.begin(), lt.end());
  std::vector<Eigen::Triplet<double>> mt;
  const double mean_mass = mass.sum() / static_cast<double>(m.n);
  for (Eigen::Index v = 0; v < n; ++v) mt.emplace_back(v, v, mass[v] > 0 ? mass[v] : 1e-12 * mean_mass);
  M.setFromTriplets(mt.begin(), mt.end());
  const double h = edge_sum / static_cast<double>(edge_count);
  const double t = h * h;  // the paper's recommended time step, m = 1
  const Eigen::SparseMatrix<double> heat = M + t * L;
  m.heat.compute(heat);
  if (m.heat.info() != Eigen::Success) throw Error("geodesic distance: factorising the heat system failed");
  // On meshes with a boundary, the paper (section 3.3) averages the Neumann and Dirichlet heat
  // solutions, which removes most of the boundary's bias.
  std::vector<char> boundary(m.n, 0);
  {
    std::vector<std::pair<std::int32_t, std::int32_t>> edges;
    for (std::size_t f = 0; f + 2 < m.tris.size(); f += 3)
      for (int c = 0; c < 3; ++c) {
        const std::int32_t a = m.tris[f + c], b = m.tris[f + (c + 1) % 3];
        edges.emplace_back(std::min(a, b), std::max(a, b));
      }
    std::sort(edges.begin(), edges.end());
    for (std::size_t e = 0; e < edges.size();) {
      std::size_t same = e + 1;
      while (same < edges.size() && edges[same] == edges[e]) ++same;
      if (same - e == 1) boundary[edges[e].first] = boundary[edges[e].second] = 1, m.has_boundary = true;
      e = same;
    }
  }
  if (m.has_boundary) {
    std::vector<Eigen::Triplet<double>> dt;
    for (int k = 0; k < heat.outerSize(); ++k)
      for (Eigen::SparseMatrix<double>::InnerIterator it(heat, k); it; ++it)
        if (!boundary[it.row()] && !boundary[it.col()]) dt.emplace_back(it.row(), it.col(), it.value());
    for (std::size_t v = 0; v < m.n; ++v)
      if (boundary[v]) dt.emplace_back(static_cast<Eigen::Index>(v), static_cast<Eigen::Index>(v), 1.0);
    Eigen::SparseMatrix<double> heat_d(n, n);
    heat_d.setFromTriplets(dt.begin(), dt.end());
    m.heat_d.compute(heat_d);
    if (m.heat_d.info() != Eigen::Success) throw Error("geodesic distance: factorising the heat system failed");
    m.boundary = std::move(boundary);
  }
  m.poisson.compute(L + 1e-8 * M);
  if (m.poisson.info() != Eigen::Success) throw Error("geodesic distance: factorising the Poisson system failed");
}

GeodesicSolver::~GeodesicSolver() = default;
GeodesicSolver::GeodesicSolver(GeodesicSolver&&) noexcept = default;
GeodesicSolver& GeodesicSolver::operator=(GeodesicSolver&&) noexcept = default;

void GeodesicSolver::distances(std::int32_t seed, std::span<double> out) const {
  const Impl& m = *impl_;
  const auto n = static_cast<Eigen::Index>(m.n);
  // 1. Heat flow for time t from the seed: (M + t L) u = delta_seed.
  Eigen::VectorXd delta = Eigen::VectorXd::Zero(n);
  delta[seed] = 1.0;
  Eigen::VectorXd u = m.heat.solve(delta);
  if (m.has_boundary && !m.boundary[seed]) u = 0.5 * (u + m.heat_d.solve(delta));
  // 2. X = -grad u / |grad u| per face; 3. its integrated divergence per vertex.
  Eigen::VectorXd div = Eigen::VectorXd::Zero(n);
  for (std::size_t f = 0; f + 2 < m.tris.size(); f += 3) {
    const std::int32_t idx[3] = {m.tris[f], m.tris[f + 1], m.tris[f + 2]};
    const Eigen::Vector3d& p0 = m.pos[idx[0]];
    const Eigen::Vector3d& p1 = m.pos[idx[1]];
    const Eigen::Vector3d& p2 = m.pos[idx[2]];
    const Eigen::Vector3d normal2a = (p1 - p0).cross(p2 - p0);  // length = 2 area
    const double area2 = normal2a.norm();
    if (!(area2 > 0)) continue;
    const Eigen::Vector3d nrm = normal2a / area2;
    // grad u = 1/(2A) sum_i u_i (N x e_i), e_i the edge opposite vertex i, counter-clockwise.
    const Eigen::Vector3d e0 = p2 - p1, e1 = p0 - p2, e2 = p1 - p0;
    const Eigen::Vector3d grad =
        (u[idx[0]] * nrm.cross(e0) + u[idx[1]] * nrm.cross(e1) + u[idx[2]] * nrm.cross(e2)) / area2;
    const double gnorm = grad.norm();
    if (!(gnorm > 0)) continue;
    const Eigen::Vector3d X = -grad / gnorm;
    const Eigen::Vector3d* p[3] = {&p0, &p1, &p2};
    for (int c = 0; c < 3; ++c) {
      const Eigen::Vector3d& pi = *p[c];
      const Eigen::Vector3d& pj = *p[(c + 1) % 3];
      const Eigen::Vector3d& pk = *p[(c + 2) % 3];
      // cot of the angles at k (opposite edge i-j) and at j (opposite edge i-k).
      const Eigen::Vector3d ka = pi - pk, kb = pj - pk, ja = pi - pj, jb = pk - pj;
      const double cot_k = ka.dot(kb) / ka.cross(kb).norm();
      const double cot_j = ja.dot(jb) / ja.cross(jb).norm();
      div[idx[c]] += 0.5 * (cot_k * (pj - pi).dot(X) + cot_j * (pk - pi).dot(X));
    }
  }
  // 4. Poisson: Delta phi = div X, i.e. L phi = -div with L positive semi-definite.
  const Eigen::VectorXd phi = m.poisson.solve(-div);
  // Reachability: the heat flow only reaches the seed's connected component.
  std::vector<char> reached(m.n, 0);
  std::vector<std::int32_t> stack{seed};
  reached[seed] = 1;
  while (!stack.empty()) {
    const std::int32_t v = stack.back();
    stack.pop_back();
    for (std::int32_t w : m.adj[v])
      if (!reached[w]) reached[w] = 1, stack.push_back(w);
  }
  const double base = phi[seed];
  for (std::size_t v = 0; v < m.n; ++v)
    out[v] = reached[v] ? std::max(0.0, phi[static_cast<Eigen::Index>(v)] - base) : kUnreachable;
  out[seed] = 0;
}

std::vector<double> distancesFrom(DistanceMetric metric, std::span<const float> positions,
                                  std::span<const std::int32_t> triangles, std::int32_t seed) {
  std::vector<double> out(positions.size() / 3);
  if (metric == DistanceMetric::kEuclidean) {
    euclideanDistances(positions, seed, out);
    return out;
  }
  // Surface metrics walk the welded surface (vdg/geom/surface.h), so a seam of duplicated vertices
  // is crossed instead of stopping the walk: solve on the distinct surface points, then give every
  // duplicate its point's distance.
  TriMesh mesh;
  mesh.positions.assign(positions.begin(), positions.end());
  mesh.triangles.assign(triangles.begin(), triangles.end());
  const SurfaceTopology surface = SurfaceTopology::build(mesh);
  const auto weld = surface.weld();
  std::vector<std::int32_t> compact(weld.size(), -1);
  std::vector<float> points;
  points.reserve(surface.weldedVertexCount() * 3);
  for (std::size_t v = 0; v < weld.size(); ++v) {
    if (weld[v] != static_cast<std::int32_t>(v)) continue;
    compact[v] = static_cast<std::int32_t>(points.size() / 3);
    points.insert(points.end(), positions.begin() + static_cast<std::ptrdiff_t>(v * 3),
                  positions.begin() + static_cast<std::ptrdiff_t>(v * 3 + 3));
  }
  std::vector<std::int32_t> welded(surface.weldedTriangles().size());
  for (std::size_t c = 0; c < welded.size(); ++c)
    welded[c] = compact[static_cast<std::size_t>(surface.weldedTriangles()[c])];
  std::vector<double> on_points(points.size() / 3);
  const std::int32_t from = compact[static_cast<std::size_t>(weld[static_cast<std::size_t>(seed)])];
  if (metric == DistanceMetric::kEdges) {
    edgeDistances(welded, on_points.size(), from, on_points);
  } else {
    GeodesicSolver(points, welded).distances(from, on_points);
  }
  for (std::size_t v = 0; v < weld.size(); ++v)
    out[v] = on_points[static_cast<std::size_t>(compact[static_cast<std::size_t>(weld[v])])];
  return out;
}

}  // namespace vdg
