// The message of the vdg::Error that `f` throws, or "" when it throws none: tests compare whole
// messages, since a message that names the wrong file or field is a defect too.
#pragma once

#include <string>

#include "vdg/geom/error.h"

namespace vdg::testing {

template <typename F>
std::string errorOf(F f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

}  // namespace vdg::testing
