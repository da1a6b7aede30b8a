// Tidying JSON text for files people read and diff (manifests, edit logs, camera files).
#pragma once

#include <string>

namespace vdg {

// Re-flows indented JSON text (as nlohmann::json::dump(2) writes it) so that every array holding
// only numbers, booleans or nulls sits on one line: "[0.0, 0.15, -1.0]". Text inside strings is
// never changed. Input that is not JSON comes back with only such arrays touched.
std::string compactScalarArrays(const std::string& json_text);

}  // namespace vdg
