// The JSON of one edit log entry (private to src/io; see vdg/io/edit_script.h): the object
// {"camera": {...}, "image_size": [w, h], "ops": [...]} that edit logs ('entries'[i]) and studio
// recovery files ('strokes'[i]) hold. Defined in edit_script.cpp, the one home of the op JSON.
#pragma once

#include <string>

#include "json_reader.h"
#include "vdg/deform/edits.h"

namespace vdg::io {

// Reads one entry at `ctx` (its own position, e.g. "'entries'[2]"). Throws vdg::Error naming the
// key path ("'entries'[2].'ops'[0] (drag).'radius': ...") for unknown keys, a missing camera or ops
// list, and every op the edit script reader refuses.
EditLogEntry editLogEntryFrom(const Json& value, const Ctx& ctx);
// The entry as JSON, numbers in their shortest exact form. `at` names the entry in messages: an op
// out of range throws vdg::Error "AT.'ops'[1] (drag).'radius': ...".
nlohmann::ordered_json editLogEntryJson(const EditLogEntry& entry, const std::string& at);

}  // namespace vdg::io
