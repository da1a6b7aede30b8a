// Runs the real `vdg` binary as a user would, for the command-line tests.
#pragma once

#include <sys/wait.h>
#include <cstdlib>
#include <string>

#include "support/test_meshes.h"

namespace vdg::testing {

struct Result {
  int code;
  std::string out, err;
};

// Runs `vdg ARGS` from the source folder, capturing stdout and stderr separately.
inline Result runVdg(const std::string& args) {
  TempDir dir;
  const std::string out = dir.file("out"), err = dir.file("err");
  const std::string cmd = "cd '" VDG_SOURCE_DIR "' && '" VDG_BINARY "' " + args + " >'" + out + "' 2>'" + err + "'";
  const int status = std::system(cmd.c_str());
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, readText(out), readText(err)};
}

}  // namespace vdg::testing
