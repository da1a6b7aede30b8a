// JSON form of ease functions, curves, tracks and camera paths (documented in docs/anim.md).
//
// The same objects appear inside scene files later; a caller holding a larger JSON document passes
// the sub-object's text and a `where` naming the file and the key path, e.g.
// parseCurve(node["path"].dump(), "scene.json: 'nodes'[2].'path'"). Every error is a vdg::Error of
// the form "WHERE: 'key'[i].'sub': what was expected", e.g. "spec.json: 'points'[2]: expected 3
// numbers". Unknown keys are rejected (they are usually typos).
#pragma once

#include <optional>
#include <string>
#include <string_view>

#include "vdg/anim/arc_length.h"
#include "vdg/anim/camera_path.h"
#include "vdg/anim/curve.h"
#include "vdg/anim/ease.h"
#include "vdg/anim/track.h"

namespace vdg::anim {

// {"ease": "linear" | "sine" | "sinusoidal" (+ "t1", "t2") | "parabolic" (+ "a", "b")}
Ease parseEase(std::string_view json_text, const std::string& where);
// {"curve": KIND, "points": [[...], ...], "times": [...]?, "arc_length": true | false | {...}?}
RawCurve parseCurve(std::string_view json_text, const std::string& where);
// {"name"?, "type"?, "interpolation"?, "extrapolation"?, "keys": [{"time", "value", "ease"?, "in"?, "out"?}]}
RawTrack parseTrack(std::string_view json_text, const std::string& where);
// {"position": CURVE, "speed"?: EASE, "start_time"?, "end_time"?, "view"?, "center"?, "target_path"?,
//  "up"?, "tilt"?: TRACK, "fov_deg"?, "ortho_height"?}
RawCameraPath parseCameraPath(std::string_view json_text, const std::string& where);

// Current version of the animation spec format: a spec may carry "version": 1 at its top level
// (files without it are read as version 1).
inline constexpr int kAnimSpecVersion = 1;

// What `vdg sample` evaluates: exactly one of an ease, a curve, a track or a camera path.
struct AnimSpec {
  enum class Kind { kEase, kCurve, kTrack, kCameraPath };
  Kind kind = Kind::kEase;
  Ease ease;
  RawCurve curve;
  std::optional<ArcLengthOptions> arc_length;  // kCurve: reparameterise by arc length
  RawTrack track;
  RawCameraPath camera_path;
};
// An object with "ease", "curve", "track" or "camera_path" at the top (see docs/anim.md).
AnimSpec parseAnimSpec(std::string_view json_text, const std::string& where);
// Reads the file (vdg::Error naming it when unreadable) and parses it with where = path.
AnimSpec loadAnimSpec(const std::string& path);

}  // namespace vdg::anim
