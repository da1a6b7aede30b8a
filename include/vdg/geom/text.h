// Text for one-line messages, written once for every module: user text quoted and made safe,
// numbers as people write them, file-name extensions compared without letter case.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace vdg {

// How many bytes of user text a message shows unless told otherwise.
inline constexpr std::size_t kShownBytes = 60;

// `text` made safe for a one-line message: control characters escaped as oneLineText does
// (vdg/geom/error.h), cut after `max_bytes` bytes with "..." appended when cut.
std::string shownText(std::string_view text, std::size_t max_bytes = kShownBytes);

// shownText in single quotes: "'spot.obj'", "'aaaa...'".
std::string quotedText(std::string_view text, std::size_t max_bytes = kShownBytes);

// A library's multi-line message as one line: trailing line breaks and spaces dropped, the other
// line breaks turned into spaces (tinyobjloader's and tinygltf's errors span lines).
std::string joinedLines(std::string text);

// A number for a message as printf's %g writes it with `significant_digits` significant digits
// (6 by default, as printf and std::ostream): "0.5", "12", "1e-09", "1e+12", "inf", "nan".
std::string numberText(double value, int significant_digits = 6);

// True when `path` ends with `extension` (".obj"), in any letter case ("X.OBJ" is an OBJ file).
bool hasExtension(std::string_view path, std::string_view extension);

// True when `path` names a glTF file: .gltf or .glb, in any letter case.
bool hasGltfExtension(std::string_view path);

}  // namespace vdg
