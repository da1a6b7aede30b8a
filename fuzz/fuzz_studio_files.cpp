// libFuzzer target: the two files of vdg studio. The first byte chooses the parser (even: input
// event files, parseInputScript; odd: recovery files, parseStudioRecovery), the rest is the text.
// An accepted file must survive the round trip through its writer: the events compare equal, the
// recovery's text is a fixed point of format -> parse -> format. See fuzz_support.h for what counts
// as a finding.
#include <string>

#include "fuzz_support.h"
#include "vdg/io/studio_events.h"
#include "vdg/io/studio_recovery.h"

namespace {

// Writing an accepted file must not throw: that would be a writer refusing what the reader took.
template <typename F>
auto mustWrite(const char* what, F f) {
  try {
    return f();
  } catch (const vdg::Error& e) {
    std::fprintf(stderr, "FINDING: %s: an accepted file does not write or read back: %s\n", what, e.what());
    std::abort();
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace vdg;
  if (size < 1 || size > fuzz::kMaxInputBytes) return -1;
  const std::string text = fuzz::text(data + 1, size - 1);
  if (data[0] % 2 == 0) {
    fuzz::expectCleanRejection("parseInputScript", [&] {
      const InputScript script = parseInputScript(text, "EVENTS.json");
      const InputScript again =
          mustWrite("input events", [&] { return parseInputScript(formatInputScript(script), "round trip"); });
      fuzz::require(again == script, "input events changed in the round trip through formatInputScript");
    });
  } else {
    fuzz::expectCleanRejection("parseStudioRecovery", [&] {
      const StudioRecovery recovery = parseStudioRecovery(text, "RECOVERY.json");
      const std::string written = mustWrite("studio recovery", [&] { return formatStudioRecovery(recovery); });
      const std::string again = mustWrite(
          "studio recovery", [&] { return formatStudioRecovery(parseStudioRecovery(written, "round trip")); });
      fuzz::require(again == written, "a recovery file changed in the round trip through formatStudioRecovery");
    });
  }
  return 0;
}
