// Writing a user's file so that it is never left half-written.
//
// The contents are written to a temporary file in the same folder and renamed over the target
// only once complete; on any failure the temporary file is removed and the target is untouched.
#pragma once

#include <functional>
#include <ostream>
#include <string>

namespace vdg {

// Calls write(stream) on a temporary file beside `path`, then renames it to `path`.
// Throws vdg::Error naming `path` when the folder is not writable or the stream fails;
// exceptions thrown by `write` propagate after the temporary file is removed.
void writeFileAtomically(const std::string& path, const std::function<void(std::ostream&)>& write);

// Same, for callers that produce the file themselves (for instance a PNG encoder): `write`
// receives the temporary path to create; the rename happens when it returns normally.
void writeFileAtomicallyVia(const std::string& path, const std::function<void(const std::string& temp_path)>& write);

}  // namespace vdg
