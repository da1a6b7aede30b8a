// vdg morph3d A B (--t T -o OUT.obj | --count N -o DIR) [--method distance|spherical|minkowski|slices|sheets]
//                 [--voxel S] [--max-voxels N] [--axis x|y|z] [--slices N] [--quiet]
//
// 3D shape interpolation (Parent 4.10, "Shape Interpolation, Metamorphosis") from mesh A (t = 0)
// to mesh B (t = 1) by one of five methods (vdg/morph/shape_morph.h, slice_morph.h, sheet_morph.h): blended signed
// distance volumes ("Distance Fields", any closed meshes, the topology may change), Kent's spherical projection
// (star-shaped genus-0 meshes, one common connectivity), Minkowski sums (closed, best convex), Chen's slices (every cut
// one contour, star-shaped about its centre; one connectivity) or Parent's sheets (genus-0 meshes split into sheets
// recursively; one connectivity). One mesh at --t, or a sequence DIR/frame_0000.obj ... at t = i / (N - 1) with a
// camera file DIR/camera.json that frames every frame for `vdg render --camera`, and, when every frame has the same
// connectivity (the spherical, slice and sheet methods), a manifest DIR/morph.vdg.json whose animated base is the
// sequence, so `vdg render DIR/morph.vdg.json` plays it. See docs/morph3d.md.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "cli.h"
#include "vdg/geom/camera.h"
#include "vdg/geom/error.h"
#include "vdg/io/atomic_file.h"
#include "vdg/io/camera_json.h"
#include "vdg/io/mesh.h"
#include "vdg/io/obj.h"
#include "vdg/morph/budget.h"
#include "vdg/morph/shape_morph.h"
#include "vdg/morph/sheet_morph.h"
#include "vdg/morph/slice_morph.h"

namespace vdg::cli {
namespace {

namespace fs = std::filesystem;

constexpr long kMaxMorph3dFrames = 100000;
// The sequence camera (DIR/camera.json): a three-quarter view from above, so that a hole through
// the shape shows, at the distance where the sphere holding every frame fills the view with a
// margin.
constexpr double kCameraAzimuthDeg = 25.0, kCameraElevationDeg = 30.0, kCameraFovDeg = 30.0, kCameraMargin = 1.15;

struct Morph3dOptions {
  std::string a, b, output, method = "distance", axis;  // axis: default y for slices, z for sheets
  double t = -1, voxel = 0, budget = morph::kDefaultBudget;
  long long max_voxels = 0;
  long frames = 0;  // --count N (the old `--frames N` too, with a deprecation note)
  std::string frames_text;
  int slices = 32;
  bool t_given = false, frames_given = false, voxel_given = false, max_voxels_given = false, quiet = false;
  bool axis_given = false, slices_given = false;
};

// One method, built once for a sequence (the distance volumes and the common connectivity are
// computed once; the Minkowski sum is computed per frame).
class Interpolator {
 public:
  Interpolator(const Morph3dOptions& opt, const TriMesh& a, const TriMesh& b) : method_(opt.method), a_(a), b_(b) {
    checkCostBeforeBuilding(opt);
    if (method_ == "distance") {
      morph::DistanceMorphOptions options;
      options.voxel_size = opt.voxel;
      if (opt.max_voxels_given) options.max_voxels = static_cast<std::size_t>(opt.max_voxels);
      distance_.emplace(a, b, options, opt.a, opt.b);
    } else if (method_ == "spherical") {
      common_.emplace(morph::sphericalMorph(a, b, opt.a, opt.b));
    } else if (method_ == "slices") {
      morph::SliceMorphOptions options;
      options.axis = axisOf(opt.axis, 1);
      options.slices = opt.slices;
      common_.emplace(morph::sliceMorph(a, b, options, opt.a, opt.b));
    } else if (method_ == "sheets") {
      common_.emplace(morph::sheetMorph(a, b, {.axis = axisOf(opt.axis, 2)}, opt.a, opt.b));
    } else {
      what_a_ = opt.a;
      what_b_ = opt.b;
    }
  }
  TriMesh at(double t) const {
    if (distance_) return distance_->at(t);
    if (common_) return common_->at(t);
    return morph::minkowskiMorph(a_, b_, t, what_a_, what_b_);
  }
  // The distance method's frames, once its volumes are built (their size is bounded by
  // --max-voxels): every frame blends and polygonises every active voxel.
  void checkFrameCost(const Morph3dOptions& opt) const {
    if (!distance_) return;
    const long frames = opt.frames_given ? opt.frames : 1;
    const double each = morph::distanceMorphFrameCost(*distance_);
    morph::checkBudget(each * static_cast<double>(frames), opt.budget, opt.a + " and " + opt.b,
                       std::to_string(frames) + (frames == 1 ? " frame" : " frames") + " x " +
                           morph::operationsText(each) + " for the distance volumes' voxels",
                       "give --budget N to allow more, or fewer frames or a larger --voxel");
  }

  std::string describe() const {
    if (distance_) {
      char text[64];
      std::snprintf(text, sizeof text, "distance, voxel %.4g", distance_->voxelSize());
      return text;
    }
    return method_;
  }

 private:
  static int axisOf(const std::string& name, int fallback) {
    return name.empty() ? fallback : name == "x" ? 0 : name == "y" ? 1 : 2;
  }

  // The Minkowski sums (one per frame strictly between t = 0 and 1), the slices and the sheets, from
  // the meshes.
  void checkCostBeforeBuilding(const Morph3dOptions& opt) const {
    if (method_ == "minkowski") {
      const long sums = opt.frames_given ? std::max(opt.frames - 2, 0L) : (opt.t > 0 && opt.t < 1 ? 1 : 0);
      const double each = morph::minkowskiMorphCost(a_, b_);
      morph::checkBudget(each * static_cast<double>(sums), opt.budget, opt.a + " and " + opt.b,
                         std::to_string(sums) + (sums == 1 ? " Minkowski sum" : " Minkowski sums") + " x " +
                             morph::operationsText(each) + ", the meshes having " +
                             std::to_string(morph::reflexEdgeCount(a_)) + " and " +
                             std::to_string(morph::reflexEdgeCount(b_)) + " reflex edges: non-convex sums are slow",
                         "give --budget N to allow more, or fewer frames, convex meshes or --method distance");
    } else if (method_ == "slices") {
      morph::SliceMorphOptions options;
      options.slices = opt.slices;
      morph::checkBudget(morph::sliceMorphCost(a_, b_, options), opt.budget, opt.a + " and " + opt.b,
                         std::to_string(opt.slices) + " slices x " +
                             std::to_string(a_.triangleCount() + b_.triangleCount()) + " triangles",
                         "give --budget N to allow more, or fewer --slices");
    } else if (method_ == "sheets") {
      morph::checkBudget(morph::sheetMorphCost(a_, b_), opt.budget, opt.a + " and " + opt.b,
                         "the sheets of " + std::to_string(a_.triangleCount()) + " and " +
                             std::to_string(b_.triangleCount()) + " triangles",
                         "give --budget N to allow more, or simpler meshes");
    }
  }

  std::string method_;
  const TriMesh& a_;
  const TriMesh& b_;
  std::string what_a_, what_b_;
  std::optional<morph::DistanceMorph> distance_;
  std::optional<morph::VertexMorph> common_;  // spherical, slices or sheets: one connectivity for A and B
};

std::string frameName(long i) {
  char name[32];
  std::snprintf(name, sizeof name, "frame_%04ld.obj", i);
  return name;
}

std::string header(const Morph3dOptions& opt, const Interpolator& morph, double t) {
  char text[64];
  std::snprintf(text, sizeof text, "t = %.6g", t);
  return "vdg morph3d " + opt.a + " -> " + opt.b + ": " + text + " (" + morph.describe() + ")";
}

// A camera looking at the centre of the box holding every frame, far enough for the box's sphere.
Camera sequenceCamera(const Bounds& box) {
  const Eigen::Vector3d lo(box.min[0], box.min[1], box.min[2]), hi(box.max[0], box.max[1], box.max[2]);
  const Eigen::Vector3d centre = (lo + hi) / 2;
  const double radius = std::max((hi - lo).norm() / 2, 1e-6);
  const double az = kCameraAzimuthDeg * M_PI / 180, el = kCameraElevationDeg * M_PI / 180;
  const Eigen::Vector3d towards_eye(std::sin(az) * std::cos(el), std::sin(el), std::cos(az) * std::cos(el));
  Camera camera;
  camera.target = centre;
  camera.eye = centre + towards_eye * (radius * kCameraMargin / std::sin(kCameraFovDeg * M_PI / 360));
  camera.up = Eigen::Vector3d(0, 1, 0);
  camera.fov_deg = kCameraFovDeg;
  return camera;
}

void grow(Bounds& box, const TriMesh& mesh, bool first) {
  const Bounds b = computeBounds(mesh.positions);
  for (int k = 0; k < 3; ++k) {
    box.min[k] = first ? b.min[k] : std::min(box.min[k], b.min[k]);
    box.max[k] = first ? b.max[k] : std::max(box.max[k], b.max[k]);
  }
}

void writeSequence(const Morph3dOptions& opt, const Interpolator& morph) {
  const fs::path dir(opt.output);
  std::error_code ec;
  if (fs::exists(dir, ec) && !fs::is_directory(dir, ec)) throw Error(opt.output + ": is not a folder");
  Bounds box;
  bool same_connectivity = true;
  std::vector<std::int32_t> first_triangles;
  std::size_t first_vertices = 0;
  for (long i = 0; i < opt.frames; ++i) {
    const double t = static_cast<double>(i) / static_cast<double>(opt.frames - 1);
    const TriMesh mesh = morph.at(t);
    if (i == 0) {
      // Created only once the first frame exists, so that bad input leaves nothing behind.
      makeOutputFolder(dir.string(), ec);  // removed again when the run fails
      if (ec) throw Error(opt.output + ": cannot create the folder: " + ec.message());
      first_triangles = mesh.triangles;
      first_vertices = mesh.vertexCount();
    } else {
      same_connectivity =
          same_connectivity && mesh.vertexCount() == first_vertices && mesh.triangles == first_triangles;
    }
    grow(box, mesh, i == 0);
    const std::string path = (dir / frameName(i)).string();
    writeObj(path, mesh, header(opt, morph, t));
    if (!opt.quiet)
      std::fprintf(stderr, "vdg morph3d: frame %ld/%ld (t = %.4g): %s, %zu triangles\n", i + 1, opt.frames, t,
                   path.c_str(), mesh.triangleCount());
  }
  writeCameraFile((dir / "camera.json").string(), sequenceCamera(box));
  if (same_connectivity) {
    // An animated base (docs/model-format.md, version 2) with one key that is frame 0 itself: no
    // view-dependent change, just the sequence.
    const std::string manifest =
        "{\n  \"version\": 2,\n  \"comment\": \"vdg morph3d " + std::string("sequence") +
        "\",\n  \"base_animation\": {\"obj_sequence\": \"frame_%04d.obj\", \"frames\": [0, " +
        std::to_string(opt.frames - 1) +
        "]},\n  \"keys\": [{\"name\": \"rest\", \"mesh\": \"frame_0000.obj\", \"view\": [0, 0, "
        "1], \"frame\": 0}]\n}\n";
    writeFileAtomically((dir / "morph.vdg.json").string(), manifest);
  }
  if (!opt.quiet)
    std::printf("wrote %ld frames to %s (%s); camera.json%s\n", opt.frames, opt.output.c_str(),
                morph.describe().c_str(), same_connectivity ? ", morph.vdg.json (one connectivity)" : "");
}

void run(const Morph3dOptions& opt) {
  if (opt.t_given == opt.frames_given)
    throw UsageError(opt.t_given ? "--t and --count exclude each other: give one" : "give --t T or --count N");
  if ((opt.voxel_given || opt.max_voxels_given) && opt.method != "distance")
    throw UsageError(std::string(opt.voxel_given ? "--voxel" : "--max-voxels") + ": only for --method distance, not " +
                     opt.method);
  if (opt.slices_given && opt.method != "slices")
    throw UsageError("--slices: only for --method slices, not " + opt.method);
  if (opt.axis_given && opt.method != "slices" && opt.method != "sheets")
    throw UsageError("--axis: only for --method slices or sheets, not " + opt.method);
  if (opt.t_given && !hasExtension(opt.output, ".obj"))
    throw UsageError("-o: with --t, give an .obj file, got " + quotedText(opt.output));
  const TriMesh a = readMesh(opt.a), b = readMesh(opt.b);
  const Interpolator morph(opt, a, b);
  morph.checkFrameCost(opt);
  if (opt.frames_given) {
    writeSequence(opt, morph);
    return;
  }
  const TriMesh mesh = morph.at(opt.t);
  writeObj(opt.output, mesh, header(opt, morph, opt.t));
  if (!opt.quiet)
    std::printf("wrote %s (%zu vertices, %zu triangles; %s)\n", opt.output.c_str(), mesh.vertexCount(),
                mesh.triangleCount(), morph.describe().c_str());
}

}  // namespace

void addMorph3dCommand(CLI::App& app) {
  auto opt = std::make_shared<Morph3dOptions>();
  CLI::App* sub = app.add_subcommand(
      "morph3d",
      "Interpolate between two closed meshes (distance fields, spherical projection, Minkowski sums, slices, "
      "sheets)");
  sub->footer(
      "Methods (docs/morph3d.md): distance: any closed meshes, the topology may change (a sphere becomes a torus); "
      "spherical: star-shaped genus-0 meshes, vertex to vertex on one connectivity; minkowski: closed meshes, best "
      "convex (slow otherwise); slices: Chen's slices along --axis, every cut one contour star-shaped about its "
      "centre; sheets: Parent's recursive sheets, genus-0 meshes, front and back facing --axis (default z). --count N "
      "-o DIR writes DIR/frame_0000.obj ... at t = i/(N-1) and DIR/camera.json "
      "for 'vdg render FRAME.obj --camera DIR/camera.json'; a sequence of one connectivity also gets "
      "DIR/morph.vdg.json for 'vdg render DIR/morph.vdg.json --camera DIR/camera.json --count N'.\n");
  sub->add_option("A", opt->a, "Source mesh at t = 0 (.obj, .gltf, .glb; closed)")->required();
  sub->add_option("B", opt->b, "Destination mesh at t = 1 (.obj, .gltf, .glb; closed)")->required();
  sub->add_option("-o,--output", opt->output, "OUT.obj with --t, a folder with --count")->required();
  sub->add_option("--t", opt->t, "One inbetween at T (0: A, 1: B)")
      ->check(numberIn({.lo = 0, .lo_end = End::kClosed, .hi = 1, .hi_end = End::kClosed}))
      ->each([opt](const std::string&) { opt->t_given = true; });
  sub->add_option("--count", opt->frames, "A sequence of N frames, t = i/(N-1)")
      ->check(wholeNumber(2, kMaxMorph3dFrames))
      ->each([opt](const std::string&) { opt->frames_given = true; });
  sub->add_option("--frames", opt->frames_text,
                  "The old spelling of --count N, read as such in this version with a deprecation note (a range "
                  "A-B is refused: the sequence's camera frames every frame, so it is written whole)")
      ->each([opt](const std::string& text) {
        if (!isPlainCount(text))
          throw UsageError(
              "--frames: morph3d writes the whole sequence (its camera.json frames every frame); give "
              "--count N, got " +
              quotedText(text));
        noteDeprecated("--frames N", "--count N");
        const auto n = parseNumberIn(text, {2, End::kClosed, kMaxMorph3dFrames, End::kClosed, true});
        if (!n)
          throw UsageError("--frames: expected a count in [2, " + std::to_string(kMaxMorph3dFrames) + "], got " +
                           quotedText(text));
        opt->frames = static_cast<long>(*n);
        opt->frames_given = true;
      });
  sub->add_option("--method", opt->method, "distance (default), spherical, minkowski, slices or sheets")
      ->check(CLI::IsMember({"distance", "spherical", "minkowski", "slices", "sheets"}));
  sub->add_option("--voxel", opt->voxel, "Distance method: voxel size in model units (default: diagonal / 96)")
      ->check(positiveNumber())
      ->each([opt](const std::string&) { opt->voxel_given = true; });
  sub->add_option("--max-voxels", opt->max_voxels, "Distance method: refuse volumes of more voxels (default 2^28)")
      ->check(wholeNumber(1000, 1L << 40))
      ->each([opt](const std::string&) { opt->max_voxels_given = true; });
  sub->add_option("--axis", opt->axis,
                  "Slices method: the axis the cutting planes are across (x, y or z; default y); sheets method: "
                  "the axis the front sheet faces (default z)")
      ->check(CLI::IsMember({"x", "y", "z"}))
      ->each([opt](const std::string&) { opt->axis_given = true; });
  sub->add_option("--slices", opt->slices, "Slices method: how many cutting planes (default 32)")
      ->check(wholeNumber(1, 4096))
      ->each([opt](const std::string&) { opt->slices_given = true; });
  sub->add_option("--budget", opt->budget,
                  "Refuse, before the frames, work estimated above N operations (default 2e9: seconds to about a "
                  "minute; a non-convex Minkowski sum or many distance frames cost most; docs/morph3d.md, "
                  "'Budgets')")
      ->check(positiveNumber(morph::kMaxBudget));
  sub->add_flag("-q,--quiet", opt->quiet, "Print nothing on success (no progress lines)");
  sub->callback([opt] { run(*opt); });
}

}  // namespace vdg::cli
