// Recovery files of `vdg studio`: the strokes a session has not saved yet, written after every
// stroke so that a crash loses nothing (docs/studio-files.md):
//   {"version": 1, "model": "/abs/spot.vdg.json", "manifest": "/abs/spot.vdg.json", "key": "side",
//    "new_key": true, "mesh": "side.obj", "key_camera": {camera}, "logged": 0, "strokes": [{edit log entry}, ...]}
// "key_camera" is the camera object of vdg/io/camera_json.h and each stroke the edit log entry
// object of vdg/io/edit_script.h ({"camera", "image_size", "ops"}): one JSON for each, shared.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "vdg/deform/edits.h"
#include "vdg/geom/camera.h"

namespace vdg {

// Current version of the recovery file format.
inline constexpr int kStudioRecoveryVersion = 1;

struct StudioRecovery {
  std::string model{};                 // the file the session opened (absolute path)
  std::string manifest{};              // the manifest the session saves to (absolute path; may not exist yet)
  std::string key{};                   // the key the strokes edit (not empty)
  bool new_key = false;                // the key is not in the manifest yet
  std::string mesh_path{};             // new key: its mesh path relative to the manifest (not empty); else empty
  std::optional<Camera> key_camera{};  // new key: its camera (required); else none
  // Entries of the key's edit log that the strokes follow: when the session made the key current
  // its log had this many (0 for a new key). A later save in the lost session may have appended
  // some of the strokes to the log; recovery truncates the log to `logged` and replays the strokes.
  std::size_t logged = 0;
  std::vector<EditLogEntry> strokes{};  // unsaved strokes in order, each with its camera and image size
  int key_frame = 0;                    // new key: its frame of an animated base ("frame"; 0 when absent)
};
// The largest "frame" (an animated base has at most kMaxBaseFrames = 100000 frames, vdg/viewdep/model.h).
inline constexpr std::int64_t kMaxRecoveryFrame = 99'999;
// The most edit log entries `logged` may count.
inline constexpr std::int64_t kMaxLoggedEntries = 1'000'000'000;

// The file's text (version 1). Throws vdg::Error "studio recovery: 'FIELD': ..." for a recovery
// that parseStudioRecovery would refuse: an empty key, a model or manifest path that is not
// absolute, mesh/key_camera given without new_key or missing with it, an op out of range
// ("studio recovery: 'strokes'[2].'ops'[0] (drag).'radius': ...").
std::string formatStudioRecovery(const StudioRecovery& r);
// Parses a recovery file's text. Throws vdg::Error "SOURCE: KEY PATH: PROBLEM" (one line) for bad
// JSON, a missing or unknown version or key, a wrong type, and each rule above; strokes are read as
// edit log entries, with their messages ("SOURCE: 'strokes'[0].'camera'.'fov_deg': ...").
StudioRecovery parseStudioRecovery(const std::string& text, const std::string& source);
// Reads `path` (a regular file of at most kMaxJsonFileBytes, vdg/io/read_file.h) and parses it.
StudioRecovery readStudioRecovery(const std::string& path);

}  // namespace vdg
