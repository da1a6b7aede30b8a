// vdg::Error — the one exception type the library throws for bad input.
//
// Loaders, builders and validators throw it with a message that names what failed and where
// (file, line, key name, vertex index). Hot per-frame paths never throw. The command-line tool
// prints what() as one line and exits with status 1.
#pragma once

#include <stdexcept>
#include <string>

namespace vdg {

class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& message) : std::runtime_error(message) {}
};

}  // namespace vdg
