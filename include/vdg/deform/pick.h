// Naming a mesh vertex without its index: by a model-space point (the nearest vertex) or by a pixel
// of a camera's image (the vertex seen there). The picked-vertex tools of edit scripts
// (vdg/deform/edits.h: a pick's `point` or `pixel`) and the editor's mouse (vdg studio) both use
// these, so a click in the editor and a pixel in EDITS.json pick the same vertex.
#pragma once

#include <cstdint>
#include <optional>
#include <span>

#include <Eigen/Core>

#include "vdg/geom/camera.h"

namespace vdg {

// The index of the vertex of `positions` (#V x 3) nearest to `point` (the lowest index among equally
// near ones), or nothing when the mesh has no vertex or `point` is not finite.
std::optional<std::int32_t> nearestVertex(std::span<const float> positions, const Eigen::Vector3d& point);

// The vertex seen at `pixel` (x right, y down, of a `width` x `height` image of `camera`): the ray
// through the pixel's centre point is intersected with the front-facing triangles of `triangles`
// (#F x 3 indices into `positions`; counter-clockwise seen from outside) and the first one it hits
// gives the vertex nearest to the hit point (Moller-Trumbore ray-triangle intersection). Nothing
// when the ray misses every front face, or the pixel is not finite. O(#F).
std::optional<std::int32_t> vertexAtPixel(std::span<const float> positions, std::span<const std::int32_t> triangles,
                                          const Camera& camera, int width, int height, const Eigen::Vector2d& pixel);

}  // namespace vdg
