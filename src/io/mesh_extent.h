// The extent rule of every mesh reader (private to src/io): the positions a reader hands on are
// finite and their bounding box fits a float. Coordinates near the float limit (3.4e38) are finite
// one by one, but their box's diagonal is not, and every later step (bounds, voxel sizes, camera
// distances) would then silently give nothing: an empty morph, a blank render.
#pragma once

#include <span>
#include <string>

namespace vdg::io {

// Throws vdg::Error "WHERE: vertex V lies at (x, y, z)AFTER; positions must be finite" for the first
// non-finite vertex, else "WHERE: vertices A at (...) and B at (...) lie too far apartAFTER: the
// mesh's extent (D) overflows a float" when the bounding box's diagonal D (in double) is above
// the largest float; A and B bound the widest axis. `positions` is #V x 3; `after` names what
// placed them (" after the node transforms"), or is empty.
void checkMeshExtent(std::span<const float> positions, const std::string& where, const std::string& after = "");

}  // namespace vdg::io
