// The per-frame contract of the renderer (renderer.h): every invalid input to updateMesh,
// drawMesh and the overlay draws returns false and changes nothing — no GPU buffer (the next
// valid frame is identical) and no canvas pixel (compared with the canvas as it was) — and never
// throws std::out_of_range; addMesh, a set-up call, throws vdg::Error naming the triangle.
#include <gtest/gtest.h>

#include <algorithm>
#include <climits>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "support/test_meshes.h"
#include "vdg/geom/error.h"
#include "vdg/render/renderer.h"

namespace vdg::render {
namespace {

constexpr int kCanvas = 32;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
const Rgb kBackground{0.9f, 0.9f, 0.9f};

View goodView() {
  View v;
  v.viewport = {0, 0, kCanvas, kCanvas};
  v.camera.eye = Eigen::Vector3d(0.4, 0.5, 4.0);
  v.camera.target = Eigen::Vector3d::Zero();
  v.camera.fov_deg = 40.0;
  v.z_near = 0.5;
  v.z_far = 10.0;
  return v;
}

std::vector<View> badViews() {
  std::vector<View> views;
  const auto with = [&](auto change) {
    View v = goodView();
    change(v);
    views.push_back(v);
  };
  with([](View& v) { v.viewport.width = 0; });
  with([](View& v) { v.viewport.height = -3; });
  with([](View& v) { v.z_near = 0.0; });
  with([](View& v) { v.z_near = -1.0; });
  with([](View& v) { v.z_far = v.z_near; });
  with([](View& v) { v.z_far = kNaN; });
  with([](View& v) { v.z_far = std::numeric_limits<double>::infinity(); });
  with([](View& v) { v.camera.eye.x() = kNaN; });
  with([](View& v) { v.camera.target.y() = std::numeric_limits<double>::infinity(); });
  with([](View& v) { v.camera.up.z() = kNaN; });
  with([](View& v) { v.camera.eye = v.camera.target; });                // no view axis
  with([](View& v) { v.camera.up = v.camera.eye - v.camera.target; });  // up along the axis
  with([](View& v) { v.camera.up = Eigen::Vector3d::Zero(); });         // no up
  with([](View& v) { v.camera.fov_deg = 0.0; });
  with([](View& v) { v.camera.fov_deg = 180.0; });
  with([](View& v) { v.camera.fov_deg = kNaN; });
  with([](View& v) { v.camera.ortho_height = kNaN; });
  return views;
}

class RenderContract : public ::testing::Test {
 protected:
  RenderContract() : renderer_(RendererSettings{kCanvas, kCanvas, 1}), mesh_(testing::uvSphere(8, 12)) {
    id_ = renderer_.addMesh(mesh_.triangles, mesh_.vertexCount());
    normals_.resize(mesh_.positions.size());
    EXPECT_TRUE(computeVertexNormals(mesh_.positions, mesh_.triangles, normals_));
    EXPECT_TRUE(renderer_.updateMesh(id_, mesh_.positions, normals_));
    shrunk_ = mesh_.positions;
    for (float& p : shrunk_) p *= 0.4f;  // what a refused upload must not show
  }
  // The frame of the current GPU mesh.
  Image frame() {
    renderer_.clear(kBackground);
    EXPECT_TRUE(renderer_.drawMesh(id_, goodView(), MeshStyle{}));
    Image img;
    renderer_.readPixels(img);
    return img;
  }
  Image cleared() {
    renderer_.clear(kBackground);
    Image img;
    renderer_.readPixels(img);
    return img;
  }
  Image canvas() {
    Image img;
    renderer_.readPixels(img);
    return img;
  }

  Renderer renderer_;
  TriMesh mesh_;
  int id_ = -1;
  std::vector<float> normals_, shrunk_;
};

TEST_F(RenderContract, UpdateMeshRefusesBadHandlesAndSizes) {
  const Image reference = frame();
  ASSERT_NE(reference.rgba, cleared().rgba) << "the sphere must show, or the comparisons below prove nothing";
  for (int bad : {-1, id_ + 1, INT_MAX, INT_MIN}) {
    EXPECT_FALSE(renderer_.updateMesh(bad, shrunk_, normals_)) << "handle " << bad;
  }
  const std::size_t n = shrunk_.size();
  std::vector<float> longer = shrunk_;
  longer.insert(longer.end(), {0.0f, 0.0f, 0.0f});
  for (std::size_t size : {std::size_t{0}, std::size_t{3}, n - 3, n - 1}) {
    EXPECT_FALSE(renderer_.updateMesh(id_, std::span<const float>(shrunk_.data(), size), {})) << "positions " << size;
  }
  EXPECT_FALSE(renderer_.updateMesh(id_, longer, {})) << "positions one vertex too many";
  EXPECT_FALSE(renderer_.updateMesh(id_, std::span<const float>(longer.data(), n + 1), {})) << "positions n + 1";
  for (std::size_t size : {std::size_t{3}, n - 3, n - 1, n + 1, n + 3}) {
    std::vector<float> normals(size, 0.0f);
    EXPECT_FALSE(renderer_.updateMesh(id_, shrunk_, normals)) << "normals " << size;
  }
  EXPECT_EQ(frame().rgba, reference.rgba) << "a refused update changed the mesh";
  ASSERT_TRUE(renderer_.updateMesh(id_, shrunk_, {}));  // and a valid one does change it
  EXPECT_NE(frame().rgba, reference.rgba);
}

TEST_F(RenderContract, DrawMeshRefusesBadHandlesAndViews) {
  const Image empty = cleared();
  for (int bad : {-1, id_ + 1, INT_MAX, INT_MIN}) {
    EXPECT_FALSE(renderer_.drawMesh(bad, goodView(), MeshStyle{})) << "handle " << bad;
    EXPECT_EQ(canvas().rgba, empty.rgba) << "handle " << bad;
  }
  const std::vector<View> views = badViews();
  for (std::size_t i = 0; i < views.size(); ++i) {
    EXPECT_FALSE(renderer_.drawMesh(id_, views[i], MeshStyle{})) << "bad view " << i;
    EXPECT_EQ(canvas().rgba, empty.rgba) << "bad view " << i;
  }
  EXPECT_TRUE(renderer_.drawMesh(id_, goodView(), MeshStyle{}));
  EXPECT_NE(canvas().rgba, empty.rgba);
}

TEST_F(RenderContract, OverlaysRefuseBadSizesViewsAndWidths) {
  // One triangle, one segment, one dot, all in front of the camera.
  const std::vector<float> triangle = {-1, -1, 0, 1, -1, 0, 0, 1, 0};
  const std::vector<float> segment = {-1, 0, 0, 1, 0, 0};
  const std::vector<float> dot = {0, 0, 0};
  const Rgb black{0, 0, 0};
  const Image empty = cleared();
  const auto unchanged = [&](bool result, const std::string& what) {
    EXPECT_FALSE(result) << what;
    EXPECT_EQ(canvas().rgba, empty.rgba) << what;
  };
  std::vector<float> padded = triangle;
  padded.push_back(0.0f);
  for (std::size_t size : {std::size_t{3}, std::size_t{6}, std::size_t{8}, std::size_t{10}})
    unchanged(renderer_.drawTriangles(std::span<const float>(padded.data(), std::min(size, padded.size())), goodView(),
                                      MeshStyle{}),
              "triangles of size " + std::to_string(size));
  for (std::size_t size : {std::size_t{3}, std::size_t{5}, std::size_t{7}}) {
    std::vector<float> data(size, 0.0f);
    unchanged(renderer_.drawLines(data, goodView(), 2.0f, black, true), "lines of size " + std::to_string(size));
  }
  for (std::size_t size : {std::size_t{1}, std::size_t{2}, std::size_t{4}}) {
    std::vector<float> data(size, 0.0f);
    unchanged(renderer_.drawDots(data, goodView(), 4.0f, black, true), "dots of size " + std::to_string(size));
  }
  const std::vector<View> views = badViews();
  for (std::size_t i = 0; i < views.size(); ++i) {
    unchanged(renderer_.drawTriangles(triangle, views[i], MeshStyle{}), "triangles, bad view " + std::to_string(i));
    unchanged(renderer_.drawLines(segment, views[i], 2.0f, black, true), "lines, bad view " + std::to_string(i));
    unchanged(renderer_.drawDots(dot, views[i], 4.0f, black, true), "dots, bad view " + std::to_string(i));
  }
  for (float width : {0.0f, -2.0f, std::nanf(""), std::numeric_limits<float>::infinity()}) {
    unchanged(renderer_.drawLines(segment, goodView(), width, black, true), "line width " + std::to_string(width));
    unchanged(renderer_.drawDots(dot, goodView(), width, black, true), "dot diameter " + std::to_string(width));
  }
  unchanged(renderer_.drawLines(segment, goodView(), 2.0f, black, true, std::nanf("")), "line pull NaN");
  unchanged(renderer_.drawDots(dot, goodView(), 4.0f, black, true, std::nanf("")), "dot pull NaN");
  // Empty input is valid and draws nothing; real input draws.
  EXPECT_TRUE(renderer_.drawTriangles({}, goodView(), MeshStyle{}));
  EXPECT_TRUE(renderer_.drawLines({}, goodView(), 2.0f, black, true));
  EXPECT_TRUE(renderer_.drawDots({}, goodView(), 4.0f, black, true));
  EXPECT_EQ(canvas().rgba, empty.rgba);
  EXPECT_TRUE(renderer_.drawTriangles(triangle, goodView(), MeshStyle{}));
  EXPECT_NE(canvas().rgba, empty.rgba);
}

TEST_F(RenderContract, AddMeshThrowsNamingTheTriangle) {
  std::vector<std::int32_t> triangles = mesh_.triangles;
  triangles[7] = static_cast<std::int32_t>(mesh_.vertexCount());
  try {
    (void)renderer_.addMesh(triangles, mesh_.vertexCount());
    ADD_FAILURE() << "no vdg::Error";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), "render: addMesh: triangle 2 refers to vertex " +
                                         std::to_string(mesh_.vertexCount()) + ", but the mesh has " +
                                         std::to_string(mesh_.vertexCount()) + " vertices");
  }
  triangles = mesh_.triangles;
  triangles[0] = -1;
  EXPECT_THROW((void)renderer_.addMesh(triangles, mesh_.vertexCount()), Error);
  triangles.pop_back();
  EXPECT_THROW((void)renderer_.addMesh(triangles, mesh_.vertexCount()), Error);
  // The refused meshes got no handle: the next one is 1.
  EXPECT_EQ(renderer_.addMesh(mesh_.triangles, mesh_.vertexCount()), 1);
}

}  // namespace
}  // namespace vdg::render
