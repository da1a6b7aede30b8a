// Shared by the libFuzzer targets in fuzz/: what counts as a finding.
//
// A parser or builder answering bad input with vdg::Error is the expected outcome and is swallowed.
// Anything else is a finding: another exception type (reported here with its message, then
// abort() so that libFuzzer saves the input), a crash, a leak, a sanitizer report, or a hang.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

#include "vdg/geom/error.h"

namespace vdg::fuzz {

// Inputs longer than this are ignored (libFuzzer is run with -max_len=65536 as well): every format
// here is small, and a bounded input keeps each execution fast.
inline constexpr std::size_t kMaxInputBytes = 64 * 1024;

// Runs `f`; vdg::Error is the clean rejection of bad input, every other exception aborts.
template <typename F>
void expectCleanRejection(const char* stage, F&& f) {
  try {
    f();
  } catch (const Error&) {
  } catch (const std::exception& e) {
    std::fprintf(stderr, "FINDING: %s threw a non-vdg exception: %s\n", stage, e.what());
    std::abort();
  } catch (...) {
    std::fprintf(stderr, "FINDING: %s threw a non-std exception\n", stage);
    std::abort();
  }
}

// A property that must hold for accepted input (a round trip, a range); aborts with `what`.
inline void require(bool ok, const char* what) {
  if (!ok) {
    std::fprintf(stderr, "FINDING: %s\n", what);
    std::abort();
  }
}

inline std::string text(const std::uint8_t* data, std::size_t size) {
  return std::string(reinterpret_cast<const char*>(data), size);
}

}  // namespace vdg::fuzz
