// Cameras as JSON: the object a manifest key's "camera" field holds, and camera files
// (`vdg align -o CAMERA.json`, `vdg deform --camera CAMERA.json`):
//   {"eye": [x,y,z], "target": [x,y,z], "up": [x,y,z] (default [0,1,0]), "fov_deg": f | "ortho_height": h}
// A camera file may also carry "version": 1 (written by vdg; files without it are read as version 1).
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "vdg/geom/camera.h"

namespace vdg {

// Current camera file format version.
inline constexpr int kCameraFileVersion = 1;

// Throws vdg::Error prefixed with `where` for bad JSON, missing or unknown fields, fov outside
// (0, 180), a non-positive ortho height, or a degenerate frame (eye == target, up parallel to the
// view).
Camera parseCameraJson(const std::string& text, const std::string& where);
// One compact object (no version field: it is the form embedded in manifests and edit logs).
std::string cameraToJson(const Camera& camera);

// Camera files: read with the limits of vdg/io/read_file.h; written atomically with "version".
Camera readCameraFile(const std::string& path);
void writeCameraFile(const std::string& path, const Camera& camera);

// A list of views (`vdg weights --views FILE`): a JSON array whose items are directions [x, y, z]
// (towards the eye) or objects {"view": [x, y, z]} or {"eye": [x, y, z]} (an eye position, whose view
// is eye - center). Returns one unit direction per item. Throws vdg::Error "WHERE: [I]: ..." naming
// the item for bad JSON, an item of another shape, non-finite numbers, a zero direction or an eye
// at the centre (and a too-long or too-deep document, as every vdg JSON reader).
std::vector<Eigen::Vector3d> parseViewList(const std::string& text, const std::string& where,
                                           const Eigen::Vector3d& center);
// The same list for a model weighed by eye positions ("weights": {"space": "positions"}): every
// item must be {"eye": [x, y, z]} (finite); returns the eyes. A direction item is refused naming
// it (a direction has no distance).
std::vector<Eigen::Vector3d> parseEyeList(const std::string& text, const std::string& where);

}  // namespace vdg
