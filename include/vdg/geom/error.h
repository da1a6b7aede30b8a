// vdg::Error — the one exception type the library throws for bad input.
//
// Loaders, builders and validators throw it with a message that names what failed and where
// (file, line, key name, vertex index). Hot per-frame paths never throw. The command-line tool
// prints what() as one line and exits with status 1.
//
// The message is always one printable line: control characters that a file name, key name or
// value may carry (a newline, a NUL, an escape) are written as \n, \0, \xHH, so that a hostile
// name can neither cut the message short nor spread it over several lines.
#pragma once

#include <stdexcept>
#include <string>
#include <string_view>

namespace vdg {

// `text` with every control character (bytes 0x00-0x1F and 0x7F) escaped; other bytes unchanged.
std::string oneLineText(std::string_view text);

class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& message) : std::runtime_error(oneLineText(message)) {}
};

}  // namespace vdg
