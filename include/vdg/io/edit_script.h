// The JSON forms of edit operations, edit scripts (`vdg deform --ops EDITS.json`) and per-key edit
// logs (KEY.edits.json), documented in docs/deform.md. The data types and applying them live in
// vdg/deform/edits.h; this header holds the one conversion between them and JSON.
//
// Messages name the file, the key path, the op index and the op kind, then the field:
//   "EDITS.json: 'ops'[2] (drag).'radius': must be > 0 and finite, got -1"
//   "k.edits.json: 'entries'[0].'ops'[1] (ffd).'moves'[0].'index': component 0 = 2 is out of range [0, 1]"
// Unknown ops and unknown fields are errors; every number is checked for range before it is
// converted (checkEditOp in vdg/deform/edits.h holds the ranges). Vertex indices are checked
// against the mesh later, by validateEdits().
#pragma once

#include <string>

#include "vdg/deform/edits.h"

namespace vdg {

// Largest image_size side accepted (pixels).
inline constexpr int kMaxEditImageSide = 1 << 16;

// Parses an EDITS.json text. Throws vdg::Error as above, naming `source`.
EditScript parseEditScript(const std::string& text, const std::string& source);
// Reads the file (a regular file of bounded size, see vdg/io/read_file.h) and parses it.
EditScript readEditScript(const std::string& path);

// One op as one compact JSON object, every field written (defaults too), numbers in their
// shortest exact form: parsing it gives back the same op. Throws vdg::Error "op (drag).'radius':
// ..." for an op out of range (checkEditOp), which a file could not hold.
std::string editOpToJson(const EditOp& op);
// Parses one op object (as editOpToJson writes it); `source` names it in messages.
EditOp parseEditOp(const std::string& text, const std::string& source);

// "dir/KEY.obj" -> "dir/KEY.edits.json".
std::string editLogPath(const std::string& key_mesh_path);
// The text of an edit log file (what writeEditLog writes). Throws vdg::Error naming `log.key` for
// an op out of range.
std::string formatEditLog(const EditLog& log);
// Parses an edit log. Its origin must be "base" or a file name (no folder) ending in ".obj", read
// beside the log. Throws vdg::Error naming `source` for a malformed log.
EditLog parseEditLog(const std::string& text, const std::string& source);
// Reads and parses `path`; a missing file is an error too.
EditLog readEditLog(const std::string& path);
void writeEditLog(const std::string& path, const EditLog& log);  // atomic (vdg/io/atomic_file.h)

}  // namespace vdg
