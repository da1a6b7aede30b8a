// The camera object inside JSON documents (private to src/io; see vdg/io/camera_json.h).
#pragma once

#include "json_reader.h"
#include "vdg/geom/camera.h"

namespace vdg::io {

// Reads {eye, target, up?, fov_deg | ortho_height}; `also_allowed` names one extra key the caller
// handles (for instance "version" in a camera file), or nullptr.
Camera cameraFrom(const Json& value, const Ctx& ctx, const char* also_allowed = nullptr);
nlohmann::ordered_json cameraJson(const Camera& camera);

}  // namespace vdg::io
