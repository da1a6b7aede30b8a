// The JSON forms of edit scripts (`vdg deform --ops EDITS.json`), per-key edit logs
// (KEY.edits.json) and camera files (`vdg align -o CAMERA.json`), documented in docs/deform.md.
// The data types and applying them live in vdg/deform/edits.h; this header only reads and writes.
#pragma once

#include <string>

#include "vdg/deform/edits.h"

namespace vdg {

// Parses an EDITS.json text. Throws vdg::Error naming `source`, the op index, the op and the field:
// "EDITS.json: ops[2] (drag): 'radius' must be > 0, got -1". Unknown ops and unknown fields are
// errors. Vertex indices are checked against the mesh by validateEdits().
EditScript parseEditScript(const std::string& text, const std::string& source);
// Reads the file (a regular file of bounded size, see vdg/io/read_file.h) and parses it.
EditScript readEditScript(const std::string& path);

// "dir/KEY.obj" -> "dir/KEY.edits.json".
std::string editLogPath(const std::string& key_mesh_path);
// Throws vdg::Error naming the file for a malformed log; a missing file is an error too.
EditLog readEditLog(const std::string& path);
void writeEditLog(const std::string& path, const EditLog& log);  // atomic

}  // namespace vdg
