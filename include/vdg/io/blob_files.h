// BLOBS.json: blobby objects, soft objects and metaballs for `vdg implicit` (Parent 4.11; the
// field functions in vdg/morph/implicit.h), documented in docs/implicit.md:
//   {"version": 1, "threshold": 0.5, "frames": [0, 47]?, "voxel": 0.03?,
//    "primitives": [{"kind": "wyvill", "center": [0, 0, 0] | TRACK, "radius": 1 | TRACK,
//                    "strength": 1 | TRACK (default 1), "blobbiness": 1 (blinn only, default 1)}]}
// TRACK is the track object of docs/anim.md ({"interpolation"?, "extrapolation"?, "keys":
// [{"time": FRAME, "value": ...}]}), key times in frames; a plain value is a constant. Kinds:
// "blinn" (or "blobby"), "wyvill" (or "soft"), "nishimura" (or "metaball"). Unknown keys are
// refused. Every error is one line naming the file and the key path:
//   "b.json: 'primitives'[1].'radius': expected a number > 0, got -1".
#pragma once

#include <string>

#include "vdg/morph/implicit.h"

namespace vdg {

// The BLOBS.json format version this vdg reads and writes.
inline constexpr int kBlobFileVersion = 1;
// Most frames a file's "frames" range may span.
inline constexpr int kMaxBlobFrames = 100000;

struct BlobFile {
  morph::RawBlobAnimation animation;  // validated (BlobAnimation::build succeeds on it)
  double voxel_size = 0;              // the file's "voxel"; 0 when not given
};

// Parses the text; `where` names it in messages. Throws vdg::Error. "frames" defaults to the
// whole frames spanned by the key times (rounded outwards, clamped to [0, 999999]), or [0, 0]
// when nothing is animated.
BlobFile parseBlobFile(const std::string& text, const std::string& where);
// Reads a regular file of at most kMaxJsonFileBytes (vdg/io/read_file.h) and parses it.
BlobFile readBlobFile(const std::string& path);

}  // namespace vdg
