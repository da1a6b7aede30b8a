// Real-world meshes in the renderer: surfaces drawn on their welded topology (seams of
// the file are not inked, true holes are), hard edges of the file kept through blending, smooth
// shading across texture seams, creases, and per-material and per-texel colours checked against
// the lighting equation (shade() with the hue rule) at chosen pixels.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <memory>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "support/allocation_counter.h"
#include "support/error_of.h"
#include "support/test_meshes.h"
#include "vdg/geom/error.h"
#include "vdg/geom/surface.h"
#include "vdg/io/obj.h"
#include "vdg/render/model_renderer.h"
#include "vdg/render/renderer.h"
#include "vdg/render/shading.h"
#include "vdg/render/silhouette.h"
#include "vdg/viewdep/model.h"

namespace vdg::render {
namespace {

const std::string kSourceDir = VDG_SOURCE_DIR;
constexpr int kCanvas = 160;
const Rgb kBackground{0.97f, 0.97f, 0.95f};
constexpr float kStroke = 3.0f;
// A shaded pixel against the equation: 8-bit rounding, float order of operations and the
// rasteriser's interpolation of equal normals leave at most this many levels.
constexpr int kShadeTolerance = 3;
// Two renderings of one surface that differ only in how the renderer stored it (float summation
// order of the normals) match within this many levels.
constexpr int kSameSurfaceTolerance = 3;
// A pixel within this many levels of the background is background (anti-aliasing leaves less).
constexpr int kBackgroundTolerance = 6;
// The outline's first and last pixel in a row lie within this many pixels (both ways) of ink.
constexpr int kOutlineReach = 2;
// Ink: every channel below this. The stroke colour is 0.06, 0.06, 0.08 (15, 15, 20); with 4
// samples a pixel three quarters covered by it is 73, half covered 131; shaded surfaces here keep
// a channel above 120.
constexpr int kInkLevel = 100;

// ---------------------------------------------------------------------------------------------
// Meshes.

// An axis-aligned cube [-1, 1]^3 split per face (24 vertices, 4 a face), CCW from outside; with
// `file_normals`, one file normal per face (as an OBJ `vn` or glTF NORMAL gives a hard-edged box).
TriMesh splitCube(bool file_normals) {
  TriMesh m;
  const std::array<Eigen::Vector3f, 6> normals{Eigen::Vector3f(1, 0, 0), Eigen::Vector3f(-1, 0, 0),
                                               Eigen::Vector3f(0, 1, 0), Eigen::Vector3f(0, -1, 0),
                                               Eigen::Vector3f(0, 0, 1), Eigen::Vector3f(0, 0, -1)};
  for (int f = 0; f < 6; ++f) {
    const Eigen::Vector3f n = normals[f];
    // u, v span the face so that u x v = n.
    const Eigen::Vector3f u =
        std::abs(n.y()) > 0.5f ? Eigen::Vector3f(0, 0, n.y()) : Eigen::Vector3f(n.z(), 0, -n.x()).normalized();
    const Eigen::Vector3f v = n.cross(u);
    const int first = static_cast<int>(m.vertexCount());
    for (const auto& [a, b] : std::array<std::pair<float, float>, 4>{{{-1, -1}, {1, -1}, {1, 1}, {-1, 1}}}) {
      const Eigen::Vector3f p = n + a * u + b * v;
      m.positions.insert(m.positions.end(), {p.x(), p.y(), p.z()});
    }
    m.triangles.insert(m.triangles.end(), {first, first + 1, first + 2, first, first + 2, first + 3});
    if (file_normals) {
      m.normals.insert(m.normals.end(), {n.x(), n.y(), n.z()});
      m.normal_triangles.insert(m.normal_triangles.end(), {f, f, f, f, f, f});
    }
  }
  return m;
}

// A UV sphere of radius 1 whose meridian at +Z (segment 0) is a texture seam: its vertices are
// duplicated with u = 0 and u = 1 (as exporters write it). With split = false the same positions
// and triangles, the seam closed by index (no duplicates, no uvs).
TriMesh seamSphere(int rings, int segments, bool split) {
  TriMesh m;
  const int columns = split ? segments + 1 : segments;
  auto add = [&](double x, double y, double z, double u, double v) {
    m.positions.insert(m.positions.end(), {static_cast<float>(x), static_cast<float>(y), static_cast<float>(z)});
    if (split) m.uvs.insert(m.uvs.end(), {static_cast<float>(u), static_cast<float>(v)});
  };
  add(0, 1, 0, 0.5, 1);
  for (int r = 1; r < rings; ++r) {
    const double theta = std::numbers::pi * r / rings;
    for (int s = 0; s < columns; ++s) {
      const double phi = 2 * std::numbers::pi * s / segments;
      add(std::sin(theta) * std::sin(phi), std::cos(theta), std::sin(theta) * std::cos(phi),
          static_cast<double>(s) / segments, 1.0 - static_cast<double>(r) / rings);
    }
  }
  add(0, -1, 0, 0.5, 0);
  const int south = static_cast<int>(m.vertexCount()) - 1;
  auto ring = [&](int r, int s) { return 1 + (r - 1) * columns + (split ? s : s % segments); };
  for (int s = 0; s < segments; ++s) m.triangles.insert(m.triangles.end(), {0, ring(1, s), ring(1, s + 1)});
  for (int r = 1; r + 1 < rings; ++r)
    for (int s = 0; s < segments; ++s) {
      m.triangles.insert(m.triangles.end(), {ring(r, s), ring(r + 1, s), ring(r + 1, s + 1)});
      m.triangles.insert(m.triangles.end(), {ring(r, s), ring(r + 1, s + 1), ring(r, s + 1)});
    }
  for (int s = 0; s < segments; ++s)
    m.triangles.insert(m.triangles.end(), {ring(rings - 1, s), south, ring(rings - 1, s + 1)});
  if (split) m.uv_triangles = m.triangles;
  return m;
}

// A plane in z = 0 of `columns` x `rows` unit cells ([0, columns] x [0, rows]), facing +Z, each
// cell two triangles with its own 4 vertices and texture coordinates (0, 0)..(1, 1) + offset.
TriMesh cellPlane(int columns, int rows, const Eigen::Vector2f& uv_offset = Eigen::Vector2f::Zero()) {
  TriMesh m;
  for (int j = 0; j < rows; ++j)
    for (int i = 0; i < columns; ++i) {
      const int first = static_cast<int>(m.vertexCount());
      for (const auto& [a, b] : std::array<std::pair<int, int>, 4>{{{0, 0}, {1, 0}, {1, 1}, {0, 1}}}) {
        m.positions.insert(m.positions.end(), {static_cast<float>(i + a), static_cast<float>(j + b), 0.0f});
        m.uvs.insert(m.uvs.end(), {a + uv_offset.x(), b + uv_offset.y()});
      }
      m.triangles.insert(m.triangles.end(), {first, first + 1, first + 2, first, first + 2, first + 3});
    }
  m.uv_triangles = m.triangles;
  return m;
}

TriMesh teapot() { return readObj(kSourceDir + "/examples/meshes/teapot.obj"); }

Material flatMaterial(const std::string& name, const Rgb& color) {
  Material m;
  m.name = name;
  m.base_color = color;
  return m;
}

// ---------------------------------------------------------------------------------------------
// Views and pixels.

Eigen::Vector3d center(const TriMesh& mesh) {
  const auto c = computeBounds(mesh.positions).center();
  return {c[0], c[1], c[2]};
}

View fitView(const TriMesh& mesh, double azimuth_deg, double elevation_deg, int size = kCanvas) {
  const double radius = 0.5 * computeBounds(mesh.positions).diagonal();
  const double distance = fitDistance(radius, 30.0, 1.0);
  View v;
  v.viewport = {0, 0, size, size};
  v.camera = orbitCamera(center(mesh), distance, azimuth_deg, elevation_deg, 30.0);
  v.z_near = distance - 2 * radius;
  v.z_far = distance + 2 * radius;
  return v;
}

MeshStyle strokeStyle() {
  MeshStyle s;
  s.silhouette_width = kStroke;
  return s;
}

Image draw(Renderer& r, int mesh, const View& view, const MeshStyle& style) {
  r.clear(kBackground);
  EXPECT_TRUE(r.drawMesh(mesh, view, style));
  Image img;
  r.readPixels(img);
  return img;
}

// The pixel (column, row) under a model-space point, or nullopt outside the image.
std::optional<std::array<int, 2>> pixelAt(const Camera& camera, const Eigen::Vector3d& p, int size = kCanvas) {
  const Projected q = project(camera, size, size, p);
  const int x = static_cast<int>(std::floor(q.pixel.x())), y = static_cast<int>(std::floor(q.pixel.y()));
  if (q.depth <= 0 || x < 0 || y < 0 || x >= size || y >= size) return std::nullopt;
  return std::array<int, 2>{x, y};
}

Eigen::Vector2d screen(const Camera& camera, const Eigen::Vector3d& p, int size) {
  return project(camera, size, size, p).pixel;
}

Eigen::Vector3d vertex(std::span<const float> positions, std::int32_t v) {
  const auto i = static_cast<std::size_t>(v) * 3;
  return {positions[i], positions[i + 1], positions[i + 2]};
}

bool isInk(const Image& img, int x, int y) {
  const std::uint8_t* p = img.pixel(x, y);
  return p[0] < kInkLevel && p[1] < kInkLevel && p[2] < kInkLevel;
}

bool isBackground(const Image& img, int x, int y) {
  const std::uint8_t* p = img.pixel(x, y);
  for (int c = 0; c < 3; ++c)
    if (std::abs(int(p[c]) - int(std::lround(kBackground[c] * 255))) > kBackgroundTolerance) return false;
  return true;
}

// Largest channel difference between a pixel and an expected colour in [0, 1].
int channelError(const Image& img, int x, int y, const Rgb& expected) {
  const std::uint8_t* p = img.pixel(x, y);
  int worst = 0;
  for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(int(p[c]) - int(std::lround(expected[c] * 255))));
  return worst;
}

double distanceToSegment(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const Eigen::Vector2d ab = b - a;
  const double len2 = ab.squaredNorm();
  const double t = len2 > 0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (a + t * ab - p).norm();
}

// A model-space direction in camera space (what shade() takes).
std::array<float, 3> toCamera(const Camera& camera, const Eigen::Vector3d& n) {
  const Eigen::Vector3d c = viewMatrix(camera).topLeftCorner<3, 3>() * n;
  return {static_cast<float>(c.x()), static_cast<float>(c.y()), static_cast<float>(c.z())};
}

void saveOnFailure(const Image& img, const std::string& name) {
  if (::testing::Test::HasFailure()) {
    const std::string path = ::testing::TempDir() + "/" + name + ".png";
    writePng(path, img);
    std::printf("image: %s\n", path.c_str());
  }
}

// ---------------------------------------------------------------------------------------------
// Silhouette and crease edges on the welded surface (no GL).

TEST(SurfaceEdges, TextureSeamIsNotABorderAndNeverASilhouetteFromTheFront) {
  const TriMesh sphere = seamSphere(12, 16, true);
  const SurfaceTopology welded = SurfaceTopology::build(sphere);
  const SurfaceTopology unwelded = SurfaceTopology::unwelded(sphere.triangles, sphere.vertexCount());
  EXPECT_EQ(welded.borderEdgeCount(), 0u);
  EXPECT_EQ(unwelded.borderEdgeCount(), 2u * 12u);  // both sides of the 12 seam edges
  std::vector<std::uint8_t> front(sphere.triangleCount());
  std::vector<std::uint32_t> edges;
  faceFacing(sphere.positions, sphere.triangles, Eigen::Vector3f(0.3f, 0.2f, 10), front);  // the seam faces us
  silhouetteEdges(welded, front, true, edges);
  ASSERT_FALSE(edges.empty());
  for (std::uint32_t v : edges) EXPECT_LT(sphere.positions[v * 3 + 2], 0.5f) << "vertex " << v << " is on the seam";
  silhouetteEdges(unwelded, front, true, edges);
  EXPECT_TRUE(std::any_of(edges.begin(), edges.end(), [&](std::uint32_t v) {
    return sphere.positions[v * 3 + 2] > 0.9f;
  })) << "the unwelded index buffer inks the seam (what welding is for)";
}

TEST(SurfaceEdges, CreasesAreSharpEdgesBetweenFrontFaces) {
  const TriMesh cube = splitCube(false);
  const SurfaceTopology t = SurfaceTopology::build(cube);
  ASSERT_EQ(t.edgeCount(), 18u);  // 12 cube edges + 6 face diagonals
  std::vector<std::uint8_t> front(cube.triangleCount());
  std::vector<std::uint32_t> creases;
  faceFacing(cube.positions, cube.triangles, Eigen::Vector3f(5, 4, 6), front);  // +X, +Y, +Z in front
  creaseEdges(t, cube.positions, front, 30.0, creases);
  ASSERT_EQ(creases.size(), 6u);  // the three edges between the visible faces (90 degrees)
  for (std::size_t i = 0; i < creases.size(); i += 2) {
    const Eigen::Vector3d mid = 0.5 * (vertex(cube.positions, creases[i]) + vertex(cube.positions, creases[i + 1]));
    EXPECT_EQ((mid.array() > 0.5).count(), 2) << "crease at " << mid.transpose();
  }
  creaseEdges(t, cube.positions, front, 89.0, creases);
  EXPECT_EQ(creases.size(), 6u);
  creaseEdges(t, cube.positions, front, 91.0, creases);  // sharper than every edge
  EXPECT_TRUE(creases.empty());
  for (double off : {0.0, -5.0, std::nan("")}) {
    creaseEdges(t, cube.positions, front, off, creases);
    EXPECT_TRUE(creases.empty()) << off;
  }
}

TEST(SurfaceEdges, PerFrameQueriesAllocateNothingOnceReserved) {
  const TriMesh mesh = seamSphere(16, 24, true);
  const SurfaceTopology t = SurfaceTopology::build(mesh);
  std::vector<std::uint8_t> front(mesh.triangleCount());
  std::vector<std::uint32_t> silhouette, creases;
  silhouette.reserve(t.edgeCount() * 2);
  creases.reserve(t.edgeCount() * 2);
  const long allocations = vdg::testing::allocationsDuring([&] {
    for (float x : {0.0f, 3.0f, -7.0f}) {
      faceFacing(mesh.positions, mesh.triangles, Eigen::Vector3f(x, 2, 5), front);
      silhouetteEdges(t, front, true, silhouette);
      creaseEdges(t, mesh.positions, front, 5.0, creases);
    }
  });
  EXPECT_EQ(allocations, 0);
  EXPECT_FALSE(silhouette.empty());
  EXPECT_FALSE(creases.empty());  // 24 segments: 15 degrees between neighbouring faces
}

// ---------------------------------------------------------------------------------------------
// The Utah teapot: patches stitched by position only.

// Welded edges whose two faces share no original edge: the file's seams.
std::vector<std::size_t> seamEdges(const TriMesh& mesh, const SurfaceTopology& t) {
  std::vector<std::size_t> seams;
  for (std::size_t e = 0; e < t.edgeCount(); ++e) {
    const std::int32_t f0 = t.edgeFaces()[e * 2], f1 = t.edgeFaces()[e * 2 + 1];
    if (f1 < 0) continue;
    int shared = 0;
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b)
        shared += mesh.triangles[static_cast<std::size_t>(f0) * 3 + a] ==
                  mesh.triangles[static_cast<std::size_t>(f1) * 3 + b];
    if (shared < 2) seams.push_back(e);
  }
  return seams;
}

TEST(SurfaceRender, TeapotSeamsAreNotInkedAndTheOutlineStaysClosed) {
  const TriMesh pot = teapot();
  const SurfaceTopology welded = SurfaceTopology::build(pot);
  const SurfaceTopology unwelded = SurfaceTopology::unwelded(pot.triangles, pot.vertexCount());
  ASSERT_TRUE(welded.isWelded());
  ASSERT_LT(welded.borderEdgeCount(), unwelded.borderEdgeCount() / 4);
  const std::vector<std::size_t> seams = seamEdges(pot, welded);
  ASSERT_GT(seams.size(), 200u);

  constexpr int kSize = 2 * kCanvas;  // room between the seams and the outline's strokes
  Renderer r(RendererSettings{kSize, kSize, 4});
  const int surface = r.addSurface(pot, welded);
  const int index_buffer = r.addMesh(pot.triangles, pot.vertexCount());
  ASSERT_TRUE(r.updateMesh(surface, pot.positions, {}));
  std::vector<float> normals(pot.positions.size());
  ASSERT_TRUE(computeVertexNormals(pot.positions, pot.triangles, normals));
  ASSERT_TRUE(r.updateMesh(index_buffer, pot.positions, normals));

  std::vector<std::uint8_t> front(pot.triangleCount());
  std::vector<std::uint32_t> outline;
  for (const auto& [azimuth, elevation] : std::vector<std::pair<double, double>>{{30, 20}, {-70, 35}, {160, 10}}) {
    SCOPED_TRACE("azimuth " + std::to_string(azimuth) + ", elevation " + std::to_string(elevation));
    const View view = fitView(pot, azimuth, elevation, kSize);
    const Image img = draw(r, surface, view, strokeStyle());
    const Image old = draw(r, index_buffer, view, strokeStyle());

    // Seam points that are not on the silhouette from here, away from every silhouette and
    // border stroke (those are inked, seam or not).
    faceFacing(pot.positions, pot.triangles, view.camera.eye.cast<float>(), front);
    silhouetteEdges(welded, front, true, outline);
    std::vector<std::array<Eigen::Vector2d, 2>> strokes;
    for (std::size_t i = 0; i < outline.size(); i += 2)
      strokes.push_back({screen(view.camera, vertex(pot.positions, static_cast<std::int32_t>(outline[i])), kSize),
                         screen(view.camera, vertex(pot.positions, static_cast<std::int32_t>(outline[i + 1])), kSize)});
    int checked = 0, inked = 0, inked_before = 0, facing = 0;
    for (const std::size_t e : seams) {
      const std::int32_t f0 = welded.edgeFaces()[e * 2], f1 = welded.edgeFaces()[e * 2 + 1];
      if (!front[static_cast<std::size_t>(f0)] || !front[static_cast<std::size_t>(f1)]) continue;
      ++facing;
      const Eigen::Vector3d mid = 0.5 * (vertex(pot.positions, welded.edgeVertices()[e * 2]) +
                                         vertex(pot.positions, welded.edgeVertices()[e * 2 + 1]));
      const auto px = pixelAt(view.camera, mid, kSize);
      if (!px) continue;
      const Eigen::Vector2d p((*px)[0] + 0.5, (*px)[1] + 0.5);
      if (std::any_of(strokes.begin(), strokes.end(),
                      [&](const auto& s) { return distanceToSegment(p, s[0], s[1]) < kStroke + 2.0; }))
        continue;
      ++checked;
      inked += isInk(img, (*px)[0], (*px)[1]);
      inked_before += isInk(old, (*px)[0], (*px)[1]);
    }
    EXPECT_GT(checked, 15) << facing << " front-facing seam edges, " << strokes.size() << " strokes";
    EXPECT_EQ(inked, 0) << "of " << checked << " seam points";
    EXPECT_GT(inked_before, checked / 3) << "the index buffer's borders ink the seams (the check sees ink)";

    // The outer outline: the first and last object pixel of every row is ink, or (anti-aliased
    // where the outline runs nearly along the row) within kOutlineReach pixels of ink.
    int rows = 0;
    const auto nearInk = [&](int x, int y) {
      for (int dy = -kOutlineReach; dy <= kOutlineReach; ++dy)
        for (int dx = -kOutlineReach; dx <= kOutlineReach; ++dx) {
          const int u = x + dx, v = y + dy;
          if (u >= 0 && v >= 0 && u < kSize && v < kSize && isInk(img, u, v)) return true;
        }
      return false;
    };
    for (int y = 0; y < kSize; ++y) {
      int first = -1, last = -1;
      for (int x = 0; x < kSize; ++x)
        if (!isBackground(img, x, y)) {
          if (first < 0) first = x;
          last = x;
        }
      if (first < 0) continue;
      ++rows;
      EXPECT_TRUE(nearInk(first, y) && nearInk(last, y)) << "row " << y << ": object pixels " << first << ".." << last;
    }
    EXPECT_GT(rows, kSize / 3);
    saveOnFailure(img, "teapot_az" + std::to_string(static_cast<int>(azimuth)));
  }
}

// ---------------------------------------------------------------------------------------------
// Borders, creases.

// The unit sphere without the cap around +Z (vertices with z > 0.8 keep their triangles out).
TriMesh holedSphere() {
  const TriMesh s = seamSphere(16, 24, false);
  TriMesh m = s;
  m.triangles.clear();
  for (std::size_t f = 0; f < s.triangleCount(); ++f) {
    double z = 0;
    for (int c = 0; c < 3; ++c) z += s.positions[static_cast<std::size_t>(s.triangles[f * 3 + c]) * 3 + 2] / 3.0;
    if (z < 0.8) m.triangles.insert(m.triangles.end(), &s.triangles[f * 3], &s.triangles[f * 3 + 3]);
  }
  return m;
}

TEST(SurfaceRender, ARealHoleShowsItsBorderUnlessBordersAreOff) {
  const TriMesh mesh = holedSphere();
  const SurfaceTopology t = SurfaceTopology::build(mesh);
  ASSERT_GT(t.borderEdgeCount(), 10u);
  FrameOptions o;
  o.width = o.height = kCanvas;
  o.samples = 4;
  o.silhouette_width = kStroke;
  const Camera camera = fitView(mesh, 10, 15).camera;
  const auto inkedBorderPoints = [&](bool borders, int& checked) {
    o.borders = borders;
    ModelRenderer r(mesh, o);
    Image img;
    r.render(camera, img);
    int inked = 0;
    checked = 0;
    for (std::size_t e = 0; e < t.edgeCount(); ++e) {
      if (t.edgeFaces()[e * 2 + 1] >= 0) continue;
      const auto px = pixelAt(camera, 0.5 * (vertex(mesh.positions, t.edgeVertices()[e * 2]) +
                                             vertex(mesh.positions, t.edgeVertices()[e * 2 + 1])));
      if (!px) continue;
      ++checked;
      inked += isInk(img, (*px)[0], (*px)[1]);
    }
    saveOnFailure(img, borders ? "hole_borders" : "hole_no_borders");
    return inked;
  };
  int checked = 0;
  const int inked = inkedBorderPoints(true, checked);
  EXPECT_EQ(inked, checked);
  EXPECT_GT(checked, 10);
  EXPECT_EQ(inkedBorderPoints(false, checked), 0);
}

TEST(SurfaceRender, CreasesInkSharpEdgesWhenAskedFor) {
  const TriMesh cube = splitCube(false);
  FrameOptions o;
  o.width = o.height = kCanvas;
  o.samples = 4;
  o.silhouette_width = kStroke;
  const Camera camera = fitView(cube, 40, 30).camera;
  // The midpoints of the three edges between the visible faces +X, +Y, +Z.
  const std::array<Eigen::Vector3d, 3> edges{Eigen::Vector3d(1, 1, 0), Eigen::Vector3d(0, 1, 1),
                                             Eigen::Vector3d(1, 0, 1)};
  for (const float angle : {0.0f, 30.0f}) {
    o.crease_angle_deg = angle;
    ModelRenderer r(cube, o);
    Image img;
    r.render(camera, img);
    for (const Eigen::Vector3d& mid : edges) {
      const auto px = pixelAt(camera, mid);
      ASSERT_TRUE(px);
      EXPECT_EQ(isInk(img, (*px)[0], (*px)[1]), angle > 0) << "crease angle " << angle << ", edge " << mid.transpose();
    }
    saveOnFailure(img, "creases");
  }
}

// ---------------------------------------------------------------------------------------------
// Hard edges and smooth seams.

TEST(SurfaceRender, SplitCubeKeepsItsHardEdgesAfterBlending) {
  // A key that stretches the cube along Y keeps every face axis-aligned, so the blended faces
  // keep the normals +-X, +-Y, +-Z whatever the weights.
  RawViewDependentModel raw;
  raw.source = "split cube";
  raw.base = splitCube(true);
  RawKey key;
  key.name = "tall";
  key.mesh = raw.base;
  for (std::size_t v = 0; v < key.mesh.vertexCount(); ++v) key.mesh.positions[v * 3 + 1] *= 1.4f;
  key.view = Eigen::Vector3d(0.5, 0.4, 1.0).normalized();
  raw.keys.push_back(key);
  raw.center = Eigen::Vector3d::Zero();
  const ViewDependentModel model = ViewDependentModel::build(raw);

  FrameOptions o;
  o.width = o.height = kCanvas;
  o.samples = 4;
  o.silhouette_width = kStroke;
  o.color = {0.8f, 0.5f, 0.3f};  // white would leave the warm light off: faces it does not reach look alike
  const Camera camera = orbitCamera(Eigen::Vector3d::Zero(), 8.0, 35.0, 28.0, 30.0);
  ModelRenderer r(model, o);
  Image img;
  const ViewWeights w = r.render(camera, img);
  ASSERT_GT(1.0f - w.base, 0.2f) << "the frame must blend the key in";
  std::vector<float> blended(model.base().positions.size());
  ASSERT_TRUE(model.blend(w, blended));
  const double height = blended[1] > 0 ? blended[1] : -blended[1];  // |y| of a top or bottom vertex

  // Points 15% inside each visible face from its edges (30% of its half-width), clear of the
  // outline's stroke, next to the edges it shares with the other faces.
  struct Face {
    Eigen::Vector3d normal, u, v;
  };
  const std::array<Face, 3> faces{Face{{1, 0, 0}, {0, 0, -1}, {0, 1, 0}}, Face{{0, 1, 0}, {1, 0, 0}, {0, 0, -1}},
                                  Face{{0, 0, 1}, {1, 0, 0}, {0, 1, 0}}};
  std::array<Rgb, 3> expected;
  for (int f = 0; f < 3; ++f) {
    const Face& face = faces[f];
    expected[f] = shade(o.shading, o.color, toCamera(camera, face.normal));
    for (double a : {-0.7, 0.0, 0.7})
      for (double b : {-0.7, 0.0, 0.7}) {
        Eigen::Vector3d p = face.normal + a * face.u + b * face.v;
        p.y() *= height;
        const auto px = pixelAt(camera, p);
        ASSERT_TRUE(px);
        EXPECT_LE(channelError(img, (*px)[0], (*px)[1], expected[f]), kShadeTolerance)
            << "face " << face.normal.transpose() << " at (" << a << ", " << b << ")";
      }
  }
  // The faces differ as the equation says (else the check above proves nothing about edges).
  const auto levels = [](const Rgb& a, const Rgb& b) {
    float d = 0;
    for (int c = 0; c < 3; ++c) d = std::max(d, std::abs(a[c] - b[c]));
    return d * 255;
  };
  EXPECT_GT(levels(expected[0], expected[1]), 10.0f);
  EXPECT_GT(levels(expected[1], expected[2]), 10.0f);
  saveOnFailure(img, "split_cube");

  // Without file normals the same 24 vertices weld into one smooth surface: near the edges the
  // colours are no longer the faces' (what the hard edges above are kept against).
  RawViewDependentModel smooth = raw;
  smooth.base = splitCube(false);
  const ViewDependentModel smooth_model = ViewDependentModel::build(smooth);
  ModelRenderer soft(smooth_model, o);
  Image soft_img;
  soft.render(camera, soft_img);
  Eigen::Vector3d near_edge = faces[2].normal + 0.7 * faces[2].u;  // +Z face, next to the +X face
  near_edge.y() *= height;
  const auto px = pixelAt(camera, near_edge);
  ASSERT_TRUE(px);
  EXPECT_GT(channelError(soft_img, (*px)[0], (*px)[1], expected[2]), 2 * kShadeTolerance);
}

// A mesh whose coordinates lie near the float limit has an infinite extent: no camera frames it.
// The model renderer says so, naming what it draws, instead of a draw call "refused (internal
// error)" (readers refuse such glTF files first; this is the renderer's own line).
TEST(SurfaceRender, AnInfiniteExtentIsRefusedWithItsReason) {
  TriMesh huge = testing::closedBox(0, 0, 0, 1, 1, 1);
  for (float& c : huge.positions) c *= 3e38f;
  FrameOptions o;
  o.width = o.height = kCanvas;
  EXPECT_EQ(testing::errorOf([&] { ModelRenderer(huge, o); }),
            "render: the mesh: its extent overflows a float (bounding radius inf), so no camera can frame it");
}

TEST(SurfaceRender, UvSplitSphereShadesSmoothlyAcrossTheSeam) {
  const TriMesh split = seamSphere(16, 24, true);
  const TriMesh closed = seamSphere(16, 24, false);
  ASSERT_GT(split.vertexCount(), closed.vertexCount());
  FrameOptions o;
  o.width = o.height = kCanvas;
  o.samples = 4;
  o.silhouette_width = kStroke;
  o.color = {0.8f, 0.5f, 0.3f};  // warm and cool light both at work
  const Camera camera = orbitCamera(Eigen::Vector3d::Zero(), 5.0, 12.0, 10.0, 30.0);  // the seam faces us
  Image a, b;
  ModelRenderer(split, o).render(camera, a);
  ModelRenderer(closed, o).render(camera, b);
  const ImageDiff d = compareImages(a, b, kSameSurfaceTolerance);
  EXPECT_EQ(d.differing_pixels, 0) << "max channel difference " << d.max_channel_difference;
  saveOnFailure(a, "uv_split_sphere");

  // The same split sphere as a bare index buffer with per-vertex normals: the seam shows (the
  // comparison above can fail).
  Renderer r(RendererSettings{kCanvas, kCanvas, 4});
  const int id = r.addMesh(split.triangles, split.vertexCount());
  std::vector<float> normals(split.positions.size());
  ASSERT_TRUE(computeVertexNormals(split.positions, split.triangles, normals));
  ASSERT_TRUE(r.updateMesh(id, split.positions, normals));
  View v = fitView(split, 12.0, 10.0);
  v.camera = camera;
  MeshStyle style = strokeStyle();
  style.color = o.color;
  EXPECT_GT(compareImages(draw(r, id, v, style), b, kSameSurfaceTolerance).differing_pixels, 20);
}

// ---------------------------------------------------------------------------------------------
// Materials and textures against the equation.

View planeView(const TriMesh& plane) {
  const Eigen::Vector3d c = center(plane);
  View v;
  v.viewport = {0, 0, kCanvas, kCanvas};
  v.camera.target = c;
  v.camera.eye = c + Eigen::Vector3d(0, 0, 10);
  v.camera.fov_deg = 30.0;
  v.z_near = 5;
  v.z_far = 15;
  return v;
}

TEST(SurfaceRender, EachMaterialIsShadedWithItsOwnColourAndHueRule) {
  TriMesh plane = cellPlane(3, 2);
  const std::vector<Rgb> colors{
      {1.0f, 1.0f, 1.0f}, {0.5f, 0.2f, 0.7f}, {0.8f, 0.1f, 0.1f}, {0.2f, 0.7f, 0.2f}, {0.9f, 0.6f, 0.2f}};
  for (std::size_t i = 0; i < colors.size(); ++i)
    plane.materials.push_back(flatMaterial("m" + std::to_string(i), colors[i]));
  // Cells 0..4 take materials 4, 3, 2, 1, 0 (not in material order); cell 5 has none.
  for (int cell = 0; cell < 6; ++cell) {
    const int material = cell < 5 ? 4 - cell : -1;
    plane.face_materials.insert(plane.face_materials.end(), {material, material});
  }
  Renderer r(RendererSettings{kCanvas, kCanvas, 4});
  const int id = r.addSurface(plane, SurfaceTopology::build(plane));
  ASSERT_TRUE(r.updateMesh(id, plane.positions, {}));
  const View view = planeView(plane);
  MeshStyle style = strokeStyle();
  style.color = {0.3f, 0.5f, 0.9f};
  const std::array<float, 3> n{0, 0, 1};  // the plane faces the camera
  const Image img = draw(r, id, view, style);
  const Image plain = draw(r, id, view, [&] {
    MeshStyle s = style;
    s.materials = false;
    return s;
  }());
  for (int cell = 0; cell < 6; ++cell) {
    const auto px = pixelAt(view.camera, Eigen::Vector3d(cell % 3 + 0.5, cell / 3 + 0.5, 0));
    ASSERT_TRUE(px);
    const Rgb base = cell < 5 ? colors[static_cast<std::size_t>(4 - cell)] : style.color;
    EXPECT_LE(channelError(img, (*px)[0], (*px)[1], shade(style.shading, base, n)), kShadeTolerance) << "cell " << cell;
    EXPECT_LE(channelError(plain, (*px)[0], (*px)[1], shade(style.shading, style.color, n)), kShadeTolerance)
        << "cell " << cell << " without materials";
  }
  saveOnFailure(img, "materials");
}

// An 8x8 texture of 4x4 colour blocks (2x2 texels each, so bilinear filtering at a block's centre
// reads the block's colour alone); blocks cover the hue rule's cases: whitish, greys, purples,
// reds on both sides of hue 0, and hues it leaves alone.
const std::array<std::array<std::uint8_t, 3>, 16> kBlockColors{{{255, 255, 255},
                                                                {232, 230, 224},
                                                                {90, 90, 90},
                                                                {20, 20, 22},
                                                                {140, 60, 200},
                                                                {200, 50, 180},
                                                                {120, 40, 230},
                                                                {220, 30, 30},
                                                                {230, 40, 120},
                                                                {230, 60, 20},
                                                                {240, 150, 30},
                                                                {40, 180, 60},
                                                                {40, 200, 210},
                                                                {40, 60, 220},
                                                                {230, 220, 40},
                                                                {150, 90, 40}}};

std::shared_ptr<const TextureImage> blockTexture() {
  auto t = std::make_shared<TextureImage>();
  t->width = t->height = 8;
  t->rgba.resize(8 * 8 * 4);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x) {
      const auto& c = kBlockColors[static_cast<std::size_t>((y / 2) * 4 + x / 2)];
      std::uint8_t* p = &t->rgba[static_cast<std::size_t>(y * 8 + x) * 4];
      p[0] = c[0];
      p[1] = c[1];
      p[2] = c[2];
      p[3] = 255;
    }
  return t;
}

TEST(SurfaceRender, TexelsAreShadedWithTheHueRulePerTexel) {
  // Two cells with the same texture (uploaded once): the left with a white base colour and uvs in
  // [0, 1], the right tinted and with uvs in [1, 2] x [-1, 0] (the texture repeats).
  TriMesh plane = cellPlane(2, 1);
  for (int i = 4; i < 8; ++i) {
    plane.uvs[static_cast<std::size_t>(i) * 2] += 1.0f;
    plane.uvs[static_cast<std::size_t>(i) * 2 + 1] -= 1.0f;
  }
  const auto texture = blockTexture();
  const Rgb tint{0.6f, 0.85f, 1.0f};
  for (const Rgb& base : {Rgb{1.0f, 1.0f, 1.0f}, tint}) {
    Material m = flatMaterial("textured", base);
    m.texture_path = "blocks.png";
    m.texture = texture;
    plane.materials.push_back(m);
  }
  plane.face_materials = {0, 0, 1, 1};
  Renderer r(RendererSettings{kCanvas, kCanvas, 4});
  const int id = r.addSurface(plane, SurfaceTopology::build(plane));
  ASSERT_TRUE(r.updateMesh(id, plane.positions, {}));
  const View view = planeView(plane);
  MeshStyle style = strokeStyle();
  style.borders = false;  // the outer blocks lie close to the plane's border
  const Image img = draw(r, id, view, style);
  const std::array<float, 3> n{0, 0, 1};
  int hue_rule_changed = 0;
  for (int cell = 0; cell < 2; ++cell)
    for (int block = 0; block < 16; ++block) {
      const int bx = block % 4, by = block / 4;  // by counts rows from the top of the image file
      // uv origin at the bottom-left: the block's centre is at u = (bx + 0.5) / 4, v = 1 - (by + 0.5) / 4.
      const Eigen::Vector3d p(cell + (bx + 0.5) / 4.0, 1.0 - (by + 0.5) / 4.0, 0.0);
      const auto px = pixelAt(view.camera, p);
      ASSERT_TRUE(px);
      const Rgb& base = plane.materials[static_cast<std::size_t>(cell)].base_color;
      const auto& texel = kBlockColors[static_cast<std::size_t>(block)];
      Rgb cbase;
      for (int c = 0; c < 3; ++c) cbase[c] = base[c] * (texel[c] / 255.0f);
      const Rgb expected = shade(style.shading, cbase, n);
      EXPECT_LE(channelError(img, (*px)[0], (*px)[1], expected), kShadeTolerance)
          << "cell " << cell << ", block " << block;
      ShadingParams no_rule = style.shading;
      no_rule.vary_by_hue = false;
      hue_rule_changed += channelError(img, (*px)[0], (*px)[1], shade(no_rule, cbase, n)) > 2 * kShadeTolerance;
    }
  EXPECT_GT(hue_rule_changed, 8) << "the blocks exercise the hue rule";
  saveOnFailure(img, "texels");
}

// ---------------------------------------------------------------------------------------------
// Set-up errors.

TEST(SurfaceRender, AddSurfaceRefusesAnotherMeshesTopologyAndBadMaterials) {
  Renderer r(RendererSettings{16, 16, 1});
  const TriMesh sphere = vdg::testing::uvSphere(6, 8);
  const TriMesh other = vdg::testing::uvSphere(7, 8);
  try {
    (void)r.addSurface(sphere, SurfaceTopology::build(other));
    ADD_FAILURE() << "expected vdg::Error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("render: addSurface: the topology was built on another mesh"),
              std::string::npos)
        << e.what();
  }
  TriMesh flipped = sphere;
  std::swap(flipped.triangles[0], flipped.triangles[1]);
  EXPECT_THROW((void)r.addSurface(flipped, SurfaceTopology::build(sphere)), Error);

  TriMesh bad = sphere;
  bad.face_materials.assign(bad.triangleCount(), 0);  // no material 0
  try {
    (void)r.addSurface(bad, SurfaceTopology::build(sphere));
    ADD_FAILURE() << "expected vdg::Error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("render: addSurface"), std::string::npos) << e.what();
  }

  TriMesh huge = cellPlane(1, 1);
  Material m = flatMaterial("huge", {1, 1, 1});
  auto texture = std::make_shared<TextureImage>();
  texture->width = 1 << 16;  // wider than any OpenGL driver's texture
  texture->height = 1;
  texture->rgba.assign(static_cast<std::size_t>(texture->width) * 4, 255);
  m.texture = texture;
  huge.materials.push_back(m);
  huge.face_materials = {0, 0};
  try {
    (void)r.addSurface(huge, SurfaceTopology::build(huge));
    ADD_FAILURE() << "expected vdg::Error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("material 'huge': texture 65536x1 exceeds"), std::string::npos) << e.what();
  }
  EXPECT_EQ(r.addSurface(sphere, SurfaceTopology::build(sphere)), 0);  // nothing was registered before
}

TEST(SurfaceRender, UpdateMeshOnASurfaceRefusesBadSizes) {
  Renderer r(RendererSettings{16, 16, 1});
  const TriMesh sphere = vdg::testing::uvSphere(6, 8);
  const int id = r.addSurface(sphere, SurfaceTopology::build(sphere));
  const std::vector<float> shorter(sphere.positions.begin(), sphere.positions.end() - 3);
  EXPECT_FALSE(r.updateMesh(id, shorter, {}));
  EXPECT_FALSE(r.updateMesh(id, sphere.positions, shorter));
  EXPECT_FALSE(r.updateMesh(id + 1, sphere.positions, {}));
  EXPECT_TRUE(r.updateMesh(id, sphere.positions, {}));
  EXPECT_TRUE(r.updateMesh(id, sphere.positions, sphere.positions));  // unit sphere: positions are normals
}

}  // namespace
}  // namespace vdg::render
