// The camera of every output frame of `vdg render` and `vdg bake`: the orbit (orbit_options.h), or
// --camera FILE, a camera file (io/camera_json.h: one fixed camera) or a camera path (an animation
// spec {"camera_path": ...}, io/anim_json.h) sampled at --count N evenly spaced times.
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "cli.h"
#include "orbit_options.h"
#include "vdg/anim/camera_path.h"
#include "vdg/geom/camera.h"
#include "vdg/geom/error.h"
#include "vdg/io/anim_json.h"
#include "vdg/io/camera_json.h"
#include "vdg/io/read_file.h"

namespace vdg::cli {

// The camera options that vdg render and vdg bake share: the orbit (OrbitOptions), or --camera FILE
// with --count N frames along it. Each command's options derive from it.
struct CameraOptions {
  OrbitOptions camera;                           // --orbit, --azimuth, --elevation, --distance, --fov, --frames
  std::string camera_file;                       // --camera: a camera file or a camera path
  int count = 1;                                 // --count: frames along --camera
  std::vector<std::string> orbit_options_given;  // orbit options given with --camera (bad usage)
  bool count_given = false, camera_given = false;

  // The orbit's options, --camera and --count on `sub`; `camera_help` describes --camera.
  void add(CLI::App& sub, const std::string& camera_help) {
    camera.add(sub);
    sub.add_option("--camera", camera_file, camera_help);
    sub.add_option("--count", count,
                   "Frames along --camera: a camera path sampled evenly from its start to its end time, or a fixed "
                   "camera repeated (default 1)")
        ->check(wholeNumber(1, OrbitOptions::kMaxOrbitFrames));
  }

  // After parsing: which of the orbit options, --count and --camera the command line gave.
  void noteGiven(const CLI::App& sub) {
    orbit_options_given.clear();
    for (const char* name : {"--orbit", "--azimuth", "--elevation", "--distance", "--fov"})
      if (sub.count(name) > 0) orbit_options_given.push_back(name);
    count_given = sub.count("--count") > 0;
    camera_given = sub.count("--camera") > 0;
  }

  // The frames asked for, after the usage rules: --camera replaces the orbit (its options and
  // --count do not mix with the other's). Throws UsageError (exit status 2).
  FrameRange range() const {
    if (camera_given && camera_file.empty()) throw UsageError("--camera: expected a file name, got ''");
    if (!camera_file.empty() && !orbit_options_given.empty())
      throw UsageError("--camera and " + orbit_options_given.front() +
                       " exclude each other (the camera file sets the camera)");
    if (camera_file.empty() && count_given)
      throw UsageError("--count: needs --camera FILE (an orbit's frames are --orbit N)");
    if (camera_file.empty()) return camera.range();
    FrameRange r{0, count - 1};
    if (!camera.frames.empty()) {
      r = parseFrameRange(camera.frames, "--frames");
      if (r.last >= count)
        throw UsageError("--frames: expected frames within 0-" + std::to_string(count - 1) + " (--count " +
                         std::to_string(count) + "), got " + quotedText(camera.frames));
    }
    return r;
  }
};

// The camera of every output frame given by --camera FILE (the orbit is OrbitOptions).
class FrameCameras {
 public:
  // --camera FILE: a camera path when the file's top level holds "camera_path" (or another animation
  // spec's key, refused by name), else a camera file. Throws vdg::Error naming the file and key.
  void load(const std::string& path, int count) {
    count_ = count;
    const std::string text = readFileLimited(path, "camera", kMaxJsonFileBytes);
    const std::string kind = animSpecKind(text);
    if (kind.empty()) {
      fixed_ = readCameraFile(path);
      return;
    }
    if (kind != "camera_path")
      throw Error(path + ": an animation spec of kind '" + kind +
                  "', not a camera; --camera takes a camera file {\"eye\", \"target\", ...} or a camera path "
                  "{\"camera_path\": ...} (docs/render.md)");
    const anim::AnimSpec spec = anim::parseAnimSpec(text, path);
    path_.emplace(anim::CameraPath::build(spec.camera_path, path + ": 'camera_path'"));
  }

  bool fromFile() const { return fixed_.has_value() || path_.has_value(); }
  // Frame f of --count N: the fixed camera, or the path at start + (end - start) * f / (N - 1) (its
  // start for N = 1), the rule of vdg sample --samples N.
  Camera at(int f) const {
    if (fixed_) return *fixed_;
    const double lo = path_->startTime(), hi = path_->endTime();
    const double t = count_ == 1 ? lo : lo + (hi - lo) * f / (count_ - 1);
    Camera c;
    if (!path_->evaluate(t, c)) throw Error("--camera: camera path time " + std::to_string(t) + " (internal error)");
    return c;
  }

 private:
  // The animation-spec key at the top of `text` ("ease", "curve", "track", "camera_path"), or ""
  // when it has none (or is not JSON: the camera reader then says what is wrong, in vdg's words).
  // An event parser that keeps nothing, so a deeply nested file costs no recursion.
  static std::string animSpecKind(const std::string& text) {
    struct TopKeys : nlohmann::json_sax<nlohmann::json> {
      int depth = 0;
      std::string kind;
      bool null() override { return true; }
      bool boolean(bool) override { return true; }
      bool number_integer(number_integer_t) override { return true; }
      bool number_unsigned(number_unsigned_t) override { return true; }
      bool number_float(number_float_t, const string_t&) override { return true; }
      bool string(string_t&) override { return true; }
      bool binary(binary_t&) override { return true; }
      bool start_object(std::size_t) override { return ++depth, true; }
      bool end_object() override { return --depth, true; }
      bool start_array(std::size_t) override { return ++depth, true; }
      bool end_array() override { return --depth, true; }
      bool key(string_t& k) override {
        if (depth == 1 && kind.empty() && (k == "ease" || k == "curve" || k == "track" || k == "camera_path")) kind = k;
        return true;
      }
      bool parse_error(std::size_t, const std::string&, const nlohmann::detail::exception&) override { return false; }
    } keys;
    if (!nlohmann::json::sax_parse(text, &keys)) return "";
    return keys.kind;
  }

  int count_ = 1;
  std::optional<Camera> fixed_;
  std::optional<anim::CameraPath> path_;
};

}  // namespace vdg::cli
