// glTF input: every sample loads and animates as the glTF 2.0 specification says. The expected
// positions come from a small reference evaluator written here from the specification (its own
// JSON and buffer reading, Eigen's slerp), not from the code under test. Hostile files each give
// their one-line message naming the file and the element.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include <Eigen/Geometry>

#include "support/base64.h"
#include "support/error_of.h"
#include "support/test_meshes.h"
#include "vdg/anim/rig.h"
#include "vdg/io/gltf.h"
#include "vdg/io/mesh.h"
#include "vdg/io/obj.h"

namespace vdg {
namespace {

namespace fs = std::filesystem;
using Json = nlohmann::json;
using vdg::testing::errorOf;

// float32 data evaluated in double on both sides; differences are float rounding of the output.
constexpr double kPositionTol = 1e-5;

const fs::path kData = fs::path(VDG_SOURCE_DIR) / "tests/data/gltf";
const fs::path kSharedAssets = fs::path(VDG_SOURCE_DIR) / "../shared/assets/gltf";

std::string readBytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::vector<unsigned char> base64(const std::string& text) {
  std::vector<unsigned char> out;
  int bits = 0, value = 0;
  for (char c : text) {
    int d;
    if (c >= 'A' && c <= 'Z')
      d = c - 'A';
    else if (c >= 'a' && c <= 'z')
      d = c - 'a' + 26;
    else if (c >= '0' && c <= '9')
      d = c - '0' + 52;
    else if (c == '+')
      d = 62;
    else if (c == '/')
      d = 63;
    else
      break;
    value = value << 6 | d;
    bits += 6;
    if (bits >= 8) {
      bits -= 8;
      out.push_back(static_cast<unsigned char>(value >> bits & 0xff));
    }
  }
  return out;
}

// The reference: glTF 2.0 read and evaluated straight from the specification (LINEAR samplers,
// non-sparse accessors: what the samples use).
class Reference {
 public:
  explicit Reference(const fs::path& path) {
    const std::string bytes = readBytes(path);
    std::vector<unsigned char> bin;
    if (bytes.compare(0, 4, "glTF") == 0) {
      std::uint32_t json_length, bin_length;
      std::memcpy(&json_length, bytes.data() + 12, 4);
      j_ = Json::parse(bytes.substr(20, json_length));
      if (20 + json_length < bytes.size()) {
        std::memcpy(&bin_length, bytes.data() + 20 + json_length, 4);
        bin.assign(bytes.begin() + 28 + json_length, bytes.begin() + 28 + json_length + bin_length);
      }
    } else {
      j_ = Json::parse(bytes);
    }
    for (const auto& b : j_["buffers"]) {
      if (!b.contains("uri")) {
        buffers_.push_back(bin);
      } else {
        const std::string uri = b["uri"];
        if (uri.rfind("data:", 0) == 0) {
          buffers_.push_back(base64(uri.substr(uri.find(',') + 1)));
        } else {
          const std::string s = readBytes(path.parent_path() / uri);
          buffers_.emplace_back(s.begin(), s.end());
        }
      }
    }
  }

  // Accessor `a` as doubles (count x components).
  std::vector<double> read(int a) const {
    const Json& acc = j_["accessors"][a];
    const Json& view = j_["bufferViews"][acc["bufferView"].get<int>()];
    const auto& buf = buffers_[view["buffer"].get<int>()];
    static const std::map<std::string, int> kComponents = {
        {"SCALAR", 1}, {"VEC2", 2}, {"VEC3", 3}, {"VEC4", 4}, {"MAT4", 16}};
    const int n = kComponents.at(acc["type"]);
    const int type = acc["componentType"];
    const int size = type == 5126 || type == 5125 ? 4 : type == 5123 || type == 5122 ? 2 : 1;
    const std::size_t stride = view.value("byteStride", std::size_t(n * size));
    const std::size_t start = view.value("byteOffset", std::size_t(0)) + acc.value("byteOffset", std::size_t(0));
    std::vector<double> out;
    for (std::size_t i = 0; i < acc["count"].get<std::size_t>(); ++i)
      for (int c = 0; c < n; ++c) {
        const unsigned char* p = buf.data() + start + i * stride + std::size_t(c * size);
        if (type == 5126) {
          float f;
          std::memcpy(&f, p, 4);
          out.push_back(f);
        } else if (type == 5123) {
          std::uint16_t u;
          std::memcpy(&u, p, 2);
          out.push_back(acc.value("normalized", false) ? u / 65535.0 : u);
        } else if (type == 5125) {
          std::uint32_t u;
          std::memcpy(&u, p, 4);
          out.push_back(u);
        } else {
          out.push_back(acc.value("normalized", false) ? *p / 255.0 : *p);
        }
      }
    return out;
  }

  // LINEAR sampler at time t, clamped (spec 3.11, Appendix C).
  std::vector<double> sample(const Json& sampler, double t, bool rotation) const {
    const auto in = read(sampler["input"]);
    const auto out = read(sampler["output"]);
    const std::size_t w = out.size() / in.size();
    auto value = [&](std::size_t k) {
      return std::vector<double>(out.begin() + long(k * w), out.begin() + long(k * w + w));
    };
    if (t <= in.front()) return value(0);
    if (t >= in.back()) return value(in.size() - 1);
    std::size_t k = 0;
    while (!(in[k] <= t && t < in[k + 1])) ++k;
    const double u = (t - in[k]) / (in[k + 1] - in[k]);
    const auto a = value(k), b = value(k + 1);
    std::vector<double> r(w);
    if (rotation) {
      const Eigen::Quaterniond qa(a[3], a[0], a[1], a[2]), qb(b[3], b[0], b[1], b[2]);
      // The samples' keyframes are unit only to about 3 digits (SimpleSkin: (0, 0, 0.383, 0.924)):
      // the spec's quaternions are unit, so they are normalised before the slerp.
      const Eigen::Quaterniond q = qa.normalized().slerp(u, qb.normalized()).normalized();
      return {q.x(), q.y(), q.z(), q.w()};
    }
    for (std::size_t i = 0; i < w; ++i) r[i] = a[i] + u * (b[i] - a[i]);
    return r;
  }

  // Posed positions of the first node with a mesh at time t of animation 0 (-1: rest pose).
  std::vector<double> positions(int animation, double t) const {
    const Json& nodes = j_["nodes"];
    const std::size_t nn = nodes.size();
    std::vector<Eigen::Vector3d> T(nn, Eigen::Vector3d::Zero()), S(nn, Eigen::Vector3d::Ones());
    std::vector<Eigen::Quaterniond> R(nn, Eigen::Quaterniond::Identity());
    std::vector<int> parent(nn, -1);
    int mesh_node = -1;
    for (std::size_t i = 0; i < nn; ++i) {
      const Json& n = nodes[i];
      auto vec3 = [](const Json& a) {
        return Eigen::Vector3d(a[0].get<double>(), a[1].get<double>(), a[2].get<double>());
      };
      if (n.contains("translation")) T[i] = vec3(n["translation"]);
      if (n.contains("scale")) S[i] = vec3(n["scale"]);
      if (n.contains("rotation"))
        R[i] = Eigen::Quaterniond(n["rotation"][3].get<double>(), n["rotation"][0].get<double>(),
                                  n["rotation"][1].get<double>(), n["rotation"][2].get<double>());
      for (int c : n.value("children", std::vector<int>{})) parent[std::size_t(c)] = int(i);
      if (n.contains("mesh") && mesh_node < 0) mesh_node = int(i);
    }
    const Json& mesh = j_["meshes"][nodes[std::size_t(mesh_node)]["mesh"].get<int>()];
    std::vector<double> weights =
        nodes[std::size_t(mesh_node)].value("weights", mesh.value("weights", std::vector<double>{}));
    if (animation >= 0) {
      const Json& anim = j_["animations"][animation];
      for (const Json& ch : anim["channels"]) {
        const int node = ch["target"]["node"];
        const std::string path = ch["target"]["path"];
        const auto v = sample(anim["samplers"][ch["sampler"].get<int>()], t, path == "rotation");
        if (path == "translation") T[std::size_t(node)] = Eigen::Vector3d(v[0], v[1], v[2]);
        if (path == "scale") S[std::size_t(node)] = Eigen::Vector3d(v[0], v[1], v[2]);
        if (path == "rotation") R[std::size_t(node)] = Eigen::Quaterniond(v[3], v[0], v[1], v[2]);
        if (path == "weights" && node == mesh_node) weights = v;
      }
    }
    // world(i) = world(parent) * T * R * S (spec 3.5); nodes with matrices are not in the samples.
    auto world = [&](int i) {
      Eigen::Affine3d w = Eigen::Affine3d::Identity();
      for (int k = i; k >= 0; k = parent[std::size_t(k)]) {
        if (nodes[std::size_t(k)].contains("matrix")) {
          const auto m = nodes[std::size_t(k)]["matrix"].get<std::vector<double>>();  // column-major
          w = Eigen::Affine3d(Eigen::Map<const Eigen::Matrix4d>(m.data())) * w;
        } else {
          w = Eigen::Translation3d(T[std::size_t(k)]) * R[std::size_t(k)] * Eigen::Scaling(S[std::size_t(k)]) * w;
        }
      }
      return w.matrix();
    };
    std::vector<double> out;
    for (const Json& prim : mesh["primitives"]) {
      if (prim.value("mode", 4) != 4) continue;
      auto p = read(prim["attributes"]["POSITION"]);
      const std::vector<Json> targets = prim.value("targets", std::vector<Json>{});
      for (std::size_t t2 = 0; t2 < targets.size(); ++t2) {
        if (!targets[t2].contains("POSITION")) continue;
        const auto d = read(targets[t2]["POSITION"]);
        for (std::size_t i = 0; i < p.size(); ++i) p[i] += weights[t2] * d[i];
      }
      const std::size_t nv = p.size() / 3;
      const bool skinned = nodes[std::size_t(mesh_node)].contains("skin");
      std::vector<Eigen::Matrix4d> joint;
      std::vector<double> jidx, jw;
      if (skinned) {
        const Json& skin = j_["skins"][nodes[std::size_t(mesh_node)]["skin"].get<int>()];
        const auto ibm = read(skin["inverseBindMatrices"]);
        for (std::size_t k = 0; k < skin["joints"].size(); ++k)
          joint.push_back(world(skin["joints"][k]) * Eigen::Map<const Eigen::Matrix4d>(ibm.data() + 16 * k));
        jidx = read(prim["attributes"]["JOINTS_0"]);
        jw = read(prim["attributes"]["WEIGHTS_0"]);
      }
      const Eigen::Matrix4d placement = world(mesh_node);
      for (std::size_t v = 0; v < nv; ++v) {
        Eigen::Matrix4d m = Eigen::Matrix4d::Zero();
        if (skinned) {
          for (int k = 0; k < 4; ++k)
            m += jw[4 * v + std::size_t(k)] * joint[std::size_t(jidx[4 * v + std::size_t(k)])];
        } else {
          m = placement;
        }
        const Eigen::Vector4d q = m * Eigen::Vector4d(p[3 * v], p[3 * v + 1], p[3 * v + 2], 1.0);
        for (int c = 0; c < 3; ++c) out.push_back(q[c]);
      }
    }
    return out;
  }

  const Json& json() const { return j_; }

 private:
  Json j_;
  std::vector<std::vector<unsigned char>> buffers_;
};

std::vector<fs::path> samples(const fs::path& root) {
  std::vector<fs::path> out;
  if (!fs::exists(root)) return out;
  for (const auto& e : fs::recursive_directory_iterator(root))
    if (e.path().extension() == ".gltf" || e.path().extension() == ".glb") out.push_back(e.path());
  std::sort(out.begin(), out.end());
  return out;
}

void expectMatchesReference(const fs::path& file) {
  SCOPED_TRACE(file.string());
  const Rig rig = Rig::build(readGltfRig(file.string()));
  const Reference ref(file);
  std::vector<float> pos(3 * rig.vertexCount());
  for (int a = -1; a < static_cast<int>(rig.animationCount()); ++a) {
    const double d = rig.duration(a);
    for (double f : {0.0, 0.13, 0.37, 0.5, 0.81, 1.0, 1.2}) {
      const double t = f * d;
      ASSERT_TRUE(rig.evaluate(a, t, pos));
      const auto expected = ref.positions(a, t);
      ASSERT_EQ(expected.size(), pos.size());
      double scale = 1;
      for (double v : expected) scale = std::max(scale, std::abs(v));
      for (std::size_t i = 0; i < pos.size(); ++i)
        ASSERT_NEAR(pos[i], expected[i], kPositionTol * scale) << "animation " << a << " t " << t << " value " << i;
    }
  }
}

TEST(Gltf, EverySampleLoadsAndMatchesTheSpecification) {
  const auto files = samples(kData);
  ASSERT_GE(files.size(), 8u);
  for (const auto& f : files) expectMatchesReference(f);
}

TEST(Gltf, EverySharedAssetLoadsAndMatchesTheSpecification) {
  const auto files = samples(kSharedAssets);
  if (files.empty()) GTEST_SKIP() << kSharedAssets << " is not there";
  for (const auto& f : files) expectMatchesReference(f);
}

// The reference itself is checked against numbers worked out by hand from SimpleMorph's data:
// base (0,0,0) (1,0,0) (0.5,0.5,0); target 0 moves vertex 2 by (-1, 0.5... ) -- so the test of
// the reference is a known keyframe: at t = 1 s the weights are (1, 0): positions = base + target 0.
TEST(Gltf, SimpleMorphByHand) {
  const Reference ref(kData / "SimpleMorph/SimpleMorph.gltf");
  const auto base = ref.read(1), t0 = ref.read(2), t1 = ref.read(3);
  const auto times = ref.read(4), w = ref.read(5);
  ASSERT_EQ(times.size(), 5u);
  const Rig rig = Rig::build(readGltfRig((kData / "SimpleMorph/SimpleMorph.glb").string()));
  std::vector<float> pos(9);
  for (double t : {0.25, 1.0, 1.5, 2.75, 3.5}) {
    std::size_t k = 0;
    while (!(times[k] <= t && t < times[k + 1])) ++k;
    const double u = (t - times[k]) / (times[k + 1] - times[k]);
    const double w0 = w[2 * k] + u * (w[2 * k + 2] - w[2 * k]);
    const double w1 = w[2 * k + 1] + u * (w[2 * k + 3] - w[2 * k + 1]);
    ASSERT_TRUE(rig.evaluate(0, t, pos));
    for (std::size_t i = 0; i < 9; ++i) EXPECT_NEAR(pos[i], base[i] + w0 * t0[i] + w1 * t1[i], kPositionTol) << t;
  }
  // Rest pose: the mesh's default weights (0.5, 0.5).
  ASSERT_TRUE(rig.evaluate(-1, 0, pos));
  for (std::size_t i = 0; i < 9; ++i) EXPECT_NEAR(pos[i], base[i] + 0.5 * t0[i] + 0.5 * t1[i], kPositionTol);
}

// SimpleSkin by hand: joints 0 and 1 (nodes 1 and 2) sit at world translation (0, 1, 0); joint 1
// rotates about z by the animation. Both inverse bind matrices are translations (ix, iy, 0) (this
// revision of the file binds at (0.5, 1, 0), so the skinned strip is shifted by -0.5 in x). A
// vertex v with weight b on joint 1 goes to (1 - b) (v + i + (0,1,0)) + b (Rz (v + i) + (0,1,0)).
TEST(Gltf, SimpleSkinByHand) {
  const fs::path file = kData / "SimpleSkin/simple_skin.gltf";
  const Reference ref(file);
  const auto p = ref.read(1), weights = ref.read(3), ibm = ref.read(4), times = ref.read(5), rot = ref.read(6);
  const auto joints = ref.read(2);
  for (int j = 0; j < 2; ++j) ASSERT_EQ(ibm[16 * j + 12], ibm[12]) << "both joints are bound at the same point";
  const double ix = ibm[12], iy = ibm[13];
  const Rig rig = Rig::build(readGltfRig(file.string()));
  ASSERT_TRUE(rig.skinned());
  std::vector<float> pos(p.size()), skin(3 * p.size());
  for (double t : {0.0, 0.75, 1.5, 2.25, 4.9}) {
    std::size_t k = 0;
    while (k + 1 < times.size() && !(times[k] <= t && t < times[k + 1])) ++k;
    const double u = k + 1 < times.size() ? (t - times[k]) / (times[k + 1] - times[k]) : 0;
    // The keyframes rotate about z only: slerp of z rotations interpolates the angle.
    const double a0 = 2 * std::atan2(rot[4 * k + 2], rot[4 * k + 3]);
    const double a1 = k + 1 < times.size() ? 2 * std::atan2(rot[4 * k + 6], rot[4 * k + 7]) : a0;
    const double angle = a0 + u * (a1 - a0);
    ASSERT_TRUE(rig.evaluate(0, t, pos, {}, skin));
    for (std::size_t v = 0; v < p.size() / 3; ++v) {
      double b = 0;
      for (int s2 = 0; s2 < 4; ++s2)
        if (joints[4 * v + std::size_t(s2)] == 1) b += weights[4 * v + std::size_t(s2)];
      const double x = p[3 * v] + ix, y = p[3 * v + 1] + iy;
      const double rx = std::cos(angle) * x - std::sin(angle) * y, ry = std::sin(angle) * x + std::cos(angle) * y + 1;
      EXPECT_NEAR(pos[3 * v], (1 - b) * x + b * rx, kPositionTol) << "t " << t << " v " << v;
      EXPECT_NEAR(pos[3 * v + 1], (1 - b) * (y + 1) + b * ry, kPositionTol) << "t " << t << " v " << v;
      // The skin's linear part: (1 - b) I + b Rz(angle), column-major.
      EXPECT_NEAR(skin[9 * v + 0], (1 - b) + b * std::cos(angle), kPositionTol);
      EXPECT_NEAR(skin[9 * v + 1], b * std::sin(angle), kPositionTol);
      EXPECT_NEAR(skin[9 * v + 3], -b * std::sin(angle), kPositionTol);
    }
  }
}

TEST(Gltf, TargetNamesAndMeshesThroughReadMesh) {
  const RawRig cube = readGltfRig((kData / "AnimatedMorphCube/AnimatedMorphCube.glb").string());
  EXPECT_EQ(cube.target_positions.size(), 2u);
  EXPECT_EQ(cube.normals.size(), cube.mesh.positions.size());
  EXPECT_EQ(cube.target_normals[0].size(), cube.mesh.positions.size());
  const TriMesh two = readMesh((kData / "MorphPrimitivesTest/MorphPrimitivesTest.gltf").string());
  EXPECT_EQ(two.vertexCount(), 30u);
  EXPECT_EQ(two.triangleCount(), 32u);
  const TriMesh rigged = readMesh((kData / "RiggedSimple/RiggedSimple.glb").string());
  EXPECT_EQ(rigged.vertexCount(), 96u);
  const std::string text = describeGltf((kData / "RiggedSimple/RiggedSimple.glb").string());
  EXPECT_NE(text.find("96 vertices, 188 triangles"), std::string::npos) << text;
  EXPECT_NE(text.find("rotation LINEAR, 3 keyframes"), std::string::npos) << text;
}

// ---- hostile files ---------------------------------------------------------------------------

// A one-triangle glTF with its buffer as a data URI: positions (3 x VEC3 float) then indices.
Json triangle() {
  std::string bin;
  const float p[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  bin.append(reinterpret_cast<const char*>(p), sizeof(p));
  const std::uint16_t idx[4] = {0, 1, 2, 0};
  bin.append(reinterpret_cast<const char*>(idx), sizeof(idx));
  return Json::parse(R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
    "nodes": [{"mesh": 0}],
    "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
    "buffers": [{"byteLength": 44, "uri": "data:application/octet-stream;base64,)" +
                     testing::encode64(bin) + R"("}],
    "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36}, {"buffer": 0, "byteOffset": 36, "byteLength": 6}],
    "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3"},
                  {"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"}]})");
}

std::string errorFor(const Json& j) {
  return errorOf([&] { (void)parseGltfRig(j.dump(), "t.gltf"); });
}

TEST(GltfHostile, TheTriangleLoads) {
  const RawRig raw = parseGltfRig(triangle().dump(), "t.gltf");
  EXPECT_EQ(raw.mesh.vertexCount(), 3u);
  EXPECT_EQ(raw.mesh.triangleCount(), 1u);
}

TEST(GltfHostile, EachGivesItsMessage) {
  Json j = triangle();
  j["accessors"][0]["bufferView"] = 7;
  EXPECT_EQ(errorFor(j), "t.gltf: accessors[0]: bufferView 7 out of range (the file has 2)");
  j = triangle();
  j["accessors"][0]["count"] = 4;
  EXPECT_EQ(errorFor(j), "t.gltf: accessors[0]: 4 elements from byte 0 need 48 bytes, bufferViews[0] has 36");
  j = triangle();
  j["bufferViews"][1]["byteLength"] = 60;
  EXPECT_EQ(errorFor(j), "t.gltf: bufferViews[1]: bytes 36 + 60 lie outside buffers[0] (44 bytes)");
  j = triangle();
  j["accessors"][0]["componentType"] = 5123;
  EXPECT_EQ(errorFor(j),
            "t.gltf: meshes[0]: primitives[0]: POSITION: accessors[0] is UNSIGNED_SHORT VEC3, expected FLOAT VEC3");
  j = triangle();
  j["accessors"][1]["type"] = "VEC3";
  j["accessors"][1]["count"] = 1;
  EXPECT_EQ(errorFor(j),
            "t.gltf: meshes[0]: primitives[0]: indices: accessors[1] is UNSIGNED_SHORT VEC3, expected SCALAR "
            "of UNSIGNED_BYTE, UNSIGNED_SHORT or UNSIGNED_INT");
  j = triangle();
  j["accessors"][0]["count"] = 4294967295u;
  EXPECT_EQ(errorFor(j), "t.gltf: accessors[0]: count 4294967295 is more than the limit of 16777216");
  j = triangle();
  j["nodes"] = Json::parse(R"([{"mesh": 0, "children": [1]}, {"children": [2]}, {"children": [1]}])");
  EXPECT_EQ(errorFor(j), "t.gltf: nodes[1]: is a child of both nodes[0] and nodes[2]");
  j = triangle();
  j["nodes"] = Json::parse(R"([{"mesh": 0}, {"children": [2]}, {"children": [1]}])");
  EXPECT_EQ(errorFor(j), "t.gltf: nodes[1]: is its own ancestor (the node hierarchy has a cycle)");
  j = triangle();
  j["nodes"][0]["children"] = Json::array({0});
  EXPECT_EQ(errorFor(j), "t.gltf: nodes[0]: children[0]: the node is its own child (the node hierarchy has a cycle)");
  j = triangle();
  j["buffers"][0]["uri"] = "missing.bin";
  EXPECT_EQ(errorFor(j), "t.gltf: buffers: 'missing.bin' is an external file, and these bytes come without a folder");
  j = triangle();
  j["buffers"][0]["uri"] = "../secret.bin";
  EXPECT_EQ(errorFor(j),
            "t.gltf: buffers: '../secret.bin' has a '..' component (external files must lie in the "
            "glTF file's folder)");
  j = triangle();
  j["buffers"][0]["uri"] = "/etc/passwd";
  EXPECT_EQ(errorFor(j),
            "t.gltf: buffers: '/etc/passwd' is an absolute path (external files must lie in the glTF "
            "file's folder)");
  j = triangle();
  j["meshes"][0]["primitives"][0]["indices"] = 0;
  EXPECT_NE(errorFor(j).find("t.gltf: meshes[0]: primitives[0]: indices: accessors[0] is FLOAT VEC3"),
            std::string::npos);
  EXPECT_EQ(errorOf([] { (void)parseGltfRig("{\"asset\": ", "t.gltf"); }).rfind("t.gltf: ", 0), 0u);
}

TEST(GltfHostile, IndexOutOfRange) {
  Json j = triangle();
  std::string bin;
  const float p[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  bin.append(reinterpret_cast<const char*>(p), sizeof(p));
  const std::uint16_t idx[4] = {0, 1, 9, 0};
  bin.append(reinterpret_cast<const char*>(idx), sizeof(idx));
  j["buffers"][0]["uri"] = "data:application/octet-stream;base64," + testing::encode64(bin);
  EXPECT_EQ(errorFor(j),
            "t.gltf: meshes[0]: primitives[0]: indices[2] = 9 out of range (the primitive has 3 vertices)");
}

TEST(GltfHostile, SparseAccessorsAreAppliedAndChecked) {
  // A target that moves vertex 2 by (0, 0, 1) through a sparse accessor without a bufferView.
  Json j = triangle();
  std::string extra;
  const std::uint16_t sidx[2] = {2, 0};
  const float sval[3] = {0, 0, 1};
  extra.append(reinterpret_cast<const char*>(sidx), sizeof(sidx));
  extra.append(reinterpret_cast<const char*>(sval), sizeof(sval));
  j["buffers"].push_back(
      {{"byteLength", 16}, {"uri", "data:application/octet-stream;base64," + testing::encode64(extra)}});
  j["bufferViews"].push_back({{"buffer", 1}, {"byteOffset", 0}, {"byteLength", 2}});
  j["bufferViews"].push_back({{"buffer", 1}, {"byteOffset", 4}, {"byteLength", 12}});
  j["accessors"].push_back(Json::parse(R"({"componentType": 5126, "count": 3, "type": "VEC3", "sparse": {"count": 1,
      "indices": {"bufferView": 2, "componentType": 5123}, "values": {"bufferView": 3}}})"));
  j["meshes"][0]["primitives"][0]["targets"] = Json::parse(R"([{"POSITION": 2}])");
  j["meshes"][0]["weights"] = Json::array({1.0});
  const RawRig raw = parseGltfRig(j.dump(), "t.gltf");
  ASSERT_EQ(raw.target_positions.size(), 1u);
  EXPECT_EQ(raw.target_positions[0], (std::vector<float>{0, 0, 0, 0, 0, 0, 0, 0, 1}));
  j["accessors"][2]["count"] = 2;  // sparse index 2 now out of range
  EXPECT_EQ(errorFor(j), "t.gltf: accessors[2]: sparse.indices[0] = 2 out of range (the accessor has 2 elements)");
}

TEST(GltfHostile, TruncatedGlb) {
  const std::string glb = readBytes(kData / "SimpleMorph/SimpleMorph.glb");
  EXPECT_EQ(errorOf([&] { (void)parseGltfRig(glb.substr(0, glb.size() - 10), "m.glb"); }),
            "m.glb: truncated GLB: the header says " + std::to_string(glb.size()) + " bytes, the file has " +
                std::to_string(glb.size() - 10));
  EXPECT_EQ(errorOf([&] { (void)parseGltfRig(glb.substr(0, 12), "m.glb"); }),
            "m.glb: truncated GLB: 12 bytes, less than the 20 of a header and a chunk header");
  // A header whose length matches a cut file, but whose BIN chunk claims more than is left.
  std::string cut = glb.substr(0, glb.size() - 8);
  const std::uint32_t length = static_cast<std::uint32_t>(cut.size());
  std::memcpy(cut.data() + 8, &length, 4);
  EXPECT_NE(errorOf([&] { (void)parseGltfRig(cut, "m.glb"); }).find("m.glb: truncated GLB: the BIN chunk needs"),
            std::string::npos);
}

TEST(GltfHostile, DeepJsonAndFilesOnDisk) {
  const std::string deep = std::string(100000, '[') + std::string(100000, ']');
  EXPECT_NE(errorOf([&] { (void)parseGltfRig(deep, "d.gltf"); }).find("d.gltf: JSON nested deeper than 64 levels"),
            std::string::npos);
  vdg::testing::TempDir dir;
  EXPECT_EQ(errorOf([&] { (void)readGltfRig(dir.file("none.glb")); }), dir.file("none.glb") + ": no such file (glTF)");
  EXPECT_EQ(errorOf([&] { (void)readGltfRig(dir.path().string()); }).find("is a folder"),
            dir.path().string().size() + 2);
  // An external buffer that is missing next to the file.
  Json j = triangle();
  j["buffers"][0]["uri"] = "gone.bin";
  { std::ofstream(dir.file("t.gltf")) << j.dump(); }
  EXPECT_NE(errorOf([&] { (void)readGltfRig(dir.file("t.gltf")); }).find("gone.bin: no such file"), std::string::npos);
}

// ---- strictness: extents after the node transforms, glTF's own rules, vdg's lines ----

// The triangle's positions replaced by `p` (9 floats).
Json triangleAt(const std::array<float, 9>& p) {
  Json j = triangle();
  std::string bin(reinterpret_cast<const char*>(p.data()), sizeof(float) * 9);
  const std::uint16_t idx[4] = {0, 1, 2, 0};
  bin.append(reinterpret_cast<const char*>(idx), sizeof(idx));
  j["buffers"][0]["uri"] = "data:application/octet-stream;base64," + testing::encode64(bin);
  return j;
}

TEST(GltfStrict, PositionsAreFiniteAndFitAFloatAfterTheNodeTransforms) {
  Json j = triangle();
  j["nodes"][0]["scale"] = {1e39, 1.0, 1.0};  // vertex 1 at (1e39, 0, 0): inf as a float
  EXPECT_EQ(errorFor(j),
            "t.gltf: meshes[0] (nodes[0]): vertex 1 lies at (inf, 0, 0) after the node transforms; positions must be "
            "finite");
  j = triangle();
  j["nodes"][0]["scale"] = {3e38, 3e38, 1.0};  // finite, but the box's diagonal overflows
  EXPECT_EQ(errorFor(j),
            "t.gltf: meshes[0] (nodes[0]): vertices 0 at (0, 0, 0) and 1 at (3e+38, 0, 0) lie too far apart after "
            "the node transforms: the mesh's extent (4.24264e+38) overflows a float");
  j = triangleAt({0, 0, 0, 3e38f, 0, 0, 0, 3e38f, 0});  // in the file already, no node transform
  j["nodes"][0].erase("mesh");
  j["nodes"].push_back({{"mesh", 0}});
  j["scenes"][0]["nodes"] = {0, 1};
  EXPECT_EQ(errorFor(j),
            "t.gltf: meshes[0] (nodes[1]): vertices 0 at (0, 0, 0) and 1 at (3e+38, 0, 0) lie too far apart after "
            "the node transforms: the mesh's extent (4.24264e+38) overflows a float");
  // Every way in: the description (vdg info), the static mesh (render, morph3d), the rig (export).
  EXPECT_NE(errorOf([&] { (void)describeGltfData(j.dump(), "t.gltf"); }).find("overflows a float"), std::string::npos);
  vdg::testing::TempDir dir;
  { std::ofstream(dir.file("h.gltf")) << j.dump(); }
  EXPECT_NE(errorOf([&] { (void)readMesh(dir.file("h.gltf")); }).find(dir.file("h.gltf") + ": meshes[0] (nodes[1])"),
            std::string::npos);
  // The same rule for OBJ files read as meshes (readMesh): the coordinates parse, the extent does not fit.
  { std::ofstream(dir.file("h.obj")) << "v 0 0 0\nv 3e38 0 0\nv 0 3e38 0\nf 1 2 3\n"; }
  EXPECT_EQ(errorOf([&] { (void)readMesh(dir.file("h.obj")); }),
            dir.file("h.obj") +
                ": vertices 0 at (0, 0, 0) and 1 at (3e+38, 0, 0) lie too far apart: the mesh's extent (4.24264e+38) "
                "overflows a float");
  // Large but fitting: accepted as it is.
  j = triangle();
  j["nodes"][0]["scale"] = {1e37, 1e37, 1.0};
  EXPECT_EQ(errorFor(j), "");
}

TEST(GltfStrict, VersionsExtensionsAndScenes) {
  Json j = triangle();
  j["asset"]["version"] = "3.0";
  EXPECT_EQ(errorFor(j), "t.gltf: asset: version '3.0': vdg reads glTF 2.x");
  j["asset"]["version"] = "2.x";
  EXPECT_EQ(errorFor(j), "t.gltf: asset: version '2.x' is not MAJOR.MINOR");
  j["asset"]["version"] = "2.1";
  EXPECT_EQ(errorFor(j), "");  // a later 2.x stays readable as 2.0 (glTF 3.2)
  j["asset"]["minVersion"] = "2.1";
  EXPECT_EQ(errorFor(j), "t.gltf: asset: minVersion '2.1': the file needs glTF 2.1 features, vdg implements glTF 2.0");
  j["asset"]["version"] = "2.0";
  EXPECT_EQ(errorFor(j), "t.gltf: asset: minVersion '2.1' is greater than version '2.0'");
  j = triangle();
  j["extensionsUsed"] = {"KHR_draco_mesh_compression", "EXT_meshopt_compression"};
  EXPECT_EQ(errorFor(j), "");  // used, not required: the file must load without them
  // EXT_meshopt_compression and KHR_mesh_quantization are read (gltf_compress_test.cpp); others refused.
  j["extensionsRequired"] = {"EXT_meshopt_compression", "KHR_draco_mesh_compression", "KHR_texture_basisu"};
  EXPECT_EQ(
      errorFor(j),
      "t.gltf: extensionsRequired: 'KHR_draco_mesh_compression' is an extension vdg does not implement (and 1 more)");
  j["extensionsRequired"] = {"EXT_meshopt_compression", "KHR_mesh_quantization"};
  EXPECT_EQ(errorFor(j), "");  // required, and read: no bufferView is compressed, no attribute quantised
  j = triangle();
  j["scene"] = 1;
  EXPECT_EQ(errorFor(j), "t.gltf: scene: 1 out of range (the file has 1 scene)");
  j = triangle();
  j["scenes"][0]["nodes"] = {0, 3};
  EXPECT_EQ(errorFor(j), "t.gltf: scenes[0]: node 3 out of range (the file has 1)");
  j = triangle();
  j["nodes"].push_back({{"children", {0}}});
  j["scenes"][0]["nodes"] = {1, 0};
  EXPECT_EQ(errorFor(j), "t.gltf: scenes[0]: node 0 is not a root (it is a child of nodes[1])");
}

TEST(GltfStrict, RulesThatWouldGiveAWrongAnswer) {
  Json j = triangle();
  j["nodes"][0]["matrix"] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 5, 0, 0, 1};
  j["nodes"][0]["translation"] = {1, 0, 0};
  EXPECT_EQ(errorFor(j),
            "t.gltf: nodes[0]: has both a matrix and translation, rotation or scale (glTF allows one or the other)");
  j = triangle();
  j["bufferViews"][0]["byteOffset"] = -4;  // tinygltf read it as 0
  EXPECT_EQ(errorFor(j), "t.gltf: bufferViews[0]: byteOffset: expected an integer >= 0, got the number -4");
  j = triangle();
  j["accessors"][0]["normalized"] = "yes";
  EXPECT_EQ(errorFor(j), "t.gltf: accessors[0]: normalized: expected true or false, got the string \"yes\"");
  j = triangle();
  j["nodes"] = {{"mesh", 0}};  // an object, not an array: tinygltf saw no nodes
  EXPECT_EQ(errorFor(j), "t.gltf: nodes: expected an array, got an object");
  j = triangle();
  j["nodes"].push_back({{"mesh", 2}});
  EXPECT_EQ(errorFor(j), "t.gltf: nodes[1]: mesh 2 out of range (the file has 1)");
  j = triangle();
  j["meshes"][0]["primitives"][0]["attributes"]["COLOR_0"] = 5;
  EXPECT_EQ(errorFor(j), "t.gltf: meshes[0]: primitives[0]: COLOR_0: accessor 5 out of range (the file has 2)");
  j = triangle();
  j["bufferViews"][1]["byteStride"] = 4;
  j["bufferViews"][1]["byteLength"] = 8;
  j["accessors"][1]["count"] = 2;
  j["meshes"][0]["primitives"][0]["mode"] = 1;  // lines: not read
  j["meshes"][0]["primitives"].push_back({{"attributes", {{"POSITION", 0}}}, {"indices", 1}});
  EXPECT_EQ(errorFor(j),
            "t.gltf: meshes[0]: primitives[1]: indices: bufferViews[1] has byteStride 4, which an index "
            "buffer must not have");
}

TEST(GltfStrict, DuplicateChannelTargetsAreRefused) {
  Json j = triangle();
  std::string bin;
  const float times[2] = {0, 1}, values[6] = {0, 0, 0, 1, 0, 0};
  bin.append(reinterpret_cast<const char*>(times), sizeof(times));
  bin.append(reinterpret_cast<const char*>(values), sizeof(values));
  j["buffers"].push_back(
      {{"byteLength", 32}, {"uri", "data:application/octet-stream;base64," + testing::encode64(bin)}});
  j["bufferViews"].push_back({{"buffer", 1}, {"byteOffset", 0}, {"byteLength", 8}});
  j["bufferViews"].push_back({{"buffer", 1}, {"byteOffset", 8}, {"byteLength", 24}});
  j["accessors"].push_back({{"bufferView", 2}, {"componentType", 5126}, {"count", 2}, {"type", "SCALAR"}});
  j["accessors"].push_back({{"bufferView", 3}, {"componentType", 5126}, {"count", 2}, {"type", "VEC3"}});
  j["animations"] = Json::parse(R"([{"channels": [{"sampler": 0, "target": {"node": 0, "path": "translation"}}],
      "samplers": [{"input": 2, "output": 3}]}])");
  EXPECT_EQ(errorFor(j), "");
  j["animations"][0]["channels"].push_back(j["animations"][0]["channels"][0]);
  EXPECT_EQ(errorFor(j),
            "t.gltf: animations[0]: channels[1]: animates translation of node 0, as an earlier channel does");
}

// Every refusal is vdg's one line naming the file: never tinygltf's text (its placeholder folder,
// its property wording) and never a data: URI echoed back.
TEST(GltfStrict, TinygltfTextNeverLeaks) {
  std::vector<std::pair<Json, std::string>> cases;
  auto with = [&](auto change, const std::string& expected) {
    Json j = triangle();
    change(j);
    cases.emplace_back(j, expected);
  };
  with([](Json& j) { j["buffers"][0]["byteLength"] = 48; },
       "t.gltf: buffers[0]: its data: URI holds 44 bytes, byteLength says 48");
  with([](Json& j) { j["buffers"][0]["uri"] = "data:application/octet-stream;base64,****"; },
       "t.gltf: buffers[0]: its data: URI holds no base64 data");
  with([](Json& j) { j["buffers"][0]["uri"] = "data:text/html;base64," + std::string(400, 'A'); },
       "t.gltf: buffers[0]: a data: URI that is not base64 application/octet-stream or application/gltf-buffer");
  with([](Json& j) { j["buffers"][0].erase("byteLength"); }, "t.gltf: buffers[0]: byteLength is missing");
  with([](Json& j) { j["accessors"][0]["type"] = "VEC7"; },
       "t.gltf: accessors[0]: type 'VEC7' is not a glTF accessor type");
  with([](Json& j) { j["meshes"][0]["primitives"][0]["indices"] = 8; },
       "t.gltf: meshes[0]: primitives[0]: indices: accessor 8 out of range (the file has 2)");
  with([](Json& j) { j["images"] = Json::parse(R"([{"uri": "data:image/png;base64,%%%%"}])"); },
       "t.gltf: images[0]: its data: URI holds no base64 data");
  with([](Json& j) { j["images"] = Json::parse(R"([{"bufferView": 9}])"); },
       "t.gltf: images[0]: bufferView 9 out of range (the file has 2)");
  with([](Json& j) { j["cameras"] = Json::parse(R"([{"type": "perspective"}])"); },
       "t.gltf: cameras[0]: perspective is missing");
  with([](Json& j) { j["buffers"][0]["uri"] = "/" + std::string(500, 'b') + ".bin"; },
       "t.gltf: buffers: '/" + std::string(59, 'b') +
           "...' is an absolute path (external files must lie in the glTF "
           "file's folder)");
  with([](Json& j) { j["accessors"][1]["bufferView"] = 6; },
       "t.gltf: accessors[1]: bufferView 6 out of range (the file has 2)");
  with([](Json& j) { j["materials"] = Json::parse(R"([{"pbrMetallicRoughness": {"baseColorFactor": [1, 0, 0]}}])"); },
       "t.gltf: materials[0]: pbrMetallicRoughness.baseColorFactor has 3 numbers, expected 4");
  for (const auto& [j, expected] : cases) EXPECT_EQ(errorFor(j), expected);

  // A texture's refused URI is a warning, cut short too (a data: URI of a type tinygltf does not
  // decode reaches vdg as a URI).
  Json t = triangle();
  t["materials"] = Json::parse(R"([{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}])");
  t["textures"] = Json::parse(R"([{"source": 0}])");
  t["images"] = {{{"uri", "data:image/webp;base64," + std::string(300, 'Q')}}};
  t["meshes"][0]["primitives"][0]["material"] = 0;
  t["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_0"] = 0;
  t["accessors"].push_back({{"bufferView", 0}, {"componentType", 5126}, {"count", 3}, {"type", "VEC2"}});
  t["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_0"] = 2;
  std::vector<std::string> warnings;
  (void)parseGltfRig(t.dump(), "t.gltf", {}, {}, MeshReadOptions{true, false, &warnings});
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_EQ(warnings[0].find(";base64," + std::string(60, 'Q')), std::string::npos) << warnings[0];
  EXPECT_EQ(warnings[0].rfind("t.gltf: materials[0]: baseColorTexture: 'data:image/webp;base64,QQQ", 0), 0u)
      << warnings[0];

  // An external buffer shorter than its byteLength: tinygltf said "File size mismatch :
  // <vdg-gltf-folder>/link.bin, requestedBytes 44, but got 40".
  vdg::testing::TempDir dir;
  Json j = triangle();
  j["buffers"][0]["uri"] = "link.bin";
  { std::ofstream(dir.file("t.gltf")) << j.dump(); }
  { std::ofstream(dir.file("link.bin")) << std::string(40, 'x'); }
  EXPECT_EQ(errorOf([&] { (void)readGltfRig(dir.file("t.gltf")); }),
            dir.file("t.gltf") + ": buffers[0]: 'link.bin' holds 40 bytes, byteLength says 44");
  { std::ofstream(dir.file("link.bin")) << ""; }
  EXPECT_EQ(errorOf([&] { (void)readGltfRig(dir.file("t.gltf")); }),
            dir.file("t.gltf") + ": buffers[0]: 'link.bin' is empty");
}

TEST(GltfHostile, SelectionByName) {
  Json j = triangle();
  j["nodes"][0]["name"] = "Body";
  EXPECT_EQ(parseGltfRig(j.dump(), "t.gltf", {}, GltfSelect{"Body"}).mesh_node, 0);
  EXPECT_EQ(errorOf([&] { (void)parseGltfRig(j.dump(), "t.gltf", {}, GltfSelect{"Head"}); }),
            "t.gltf: no node or mesh named 'Head'");
}

}  // namespace
}  // namespace vdg
