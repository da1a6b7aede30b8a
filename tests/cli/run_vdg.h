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
//
// Under AddressSanitizer, LeakSanitizer's exit-time thread tracer now and then crashes itself
// ("Tracer caught signal 11 ... LeakSanitizer has encountered a fatal error") in a vdg process that
// rendered, while Mesa's llvmpipe threads wind down; that is the tool failing, not a finding about
// vdg (a leak is reported as "detected memory leaks" and still fails). Such a run is run again, up
// to twice. Every command the tests run writes the same files whether run once or again.
inline Result runVdg(const std::string& args) {
  constexpr int kRunsWhenTheLeakCheckerCrashes = 3;
  Result r;
  for (int run = 0; run < kRunsWhenTheLeakCheckerCrashes; ++run) {
    TempDir dir;
    const std::string out = dir.file("out"), err = dir.file("err");
    const std::string cmd = "cd '" VDG_SOURCE_DIR "' && '" VDG_BINARY "' " + args + " >'" + out + "' 2>'" + err + "'";
    const int status = std::system(cmd.c_str());
    r = {WIFEXITED(status) ? WEXITSTATUS(status) : -1, readText(out), readText(err)};
    if (r.err.find("LeakSanitizer has encountered a fatal error") == std::string::npos) break;
  }
  return r;
}

}  // namespace vdg::testing
