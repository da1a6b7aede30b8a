// Cameras as JSON: the object a manifest key's "camera" field holds, and camera files
// (`vdg align -o CAMERA.json`, `vdg deform --camera CAMERA.json`):
//   {"eye": [x,y,z], "target": [x,y,z], "up": [x,y,z] (default [0,1,0]), "fov_deg": f | "ortho_height": h}
// A camera file may also carry "version": 1 (written by vdg; files without it are read as version 1).
#pragma once

#include <string>

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

}  // namespace vdg
