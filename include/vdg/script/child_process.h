// The backstop of the script sandbox: vdg run runs a script in a child process with operating-system
// limits, so that nothing a script does (Lua pattern matching inside one C call, a slow load, a
// path the instruction budget does not see) can pin a CPU or take the machine's memory past them.
//
//   parent: runLimitedChild(args) --> the same program again (/proc/self/exe, fork + exec at once:
//           the parent may have threads, a forked copy that kept running could deadlock in them)
//           --> waits, forwarding SIGINT, SIGTERM, SIGHUP, SIGQUIT --> ChildOutcome
//   child:  inLimitedChild() --> runs the script under RLIMIT_CPU (and RLIMIT_AS), announcing the
//           files it makes (announceCreated) --> liftLimits --> renders --> exits as usual
//
// Linux only (/proc/self/exe, PR_SET_PDEATHSIG).
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace vdg::script {

inline constexpr int kDefaultCpuSeconds = 120;    // vdg run --cpu-seconds
inline constexpr int kMaxCpuSeconds = 1'000'000;  // about 11.5 days

struct ProcessLimits {
  int cpu_seconds = kDefaultCpuSeconds;  // 1..kMaxCpuSeconds: RLIMIT_CPU's soft limit (then SIGXCPU)
  // RLIMIT_AS: the address space the child may use beyond what this process has (bytes); 0 or a
  // build with AddressSanitizer (which reserves terabytes of address space): no such limit.
  std::size_t address_space = std::size_t{16} << 30;
};

enum class ChildEnd {
  kExited,       // the child exited: `code` is its exit status
  kSignaled,     // the child was killed by signal `code`
  kCpuExceeded,  // the child was killed for spending its CPU time (SIGXCPU, or SIGKILL past the limit)
};

struct ChildOutcome {
  ChildEnd end = ChildEnd::kExited;
  int code = 0;
  double cpu_seconds = 0;            // CPU time the child used (user + system)
  std::vector<std::string> created;  // what the child announced (announceCreated), in order
};

// Runs this program again with the arguments `args` (args[0] is the name it is given) as the
// limited child: RLIMIT_CPU (soft) = limits.cpu_seconds, RLIMIT_AS as above, RLIMIT_CORE 0, killed
// when this process dies, the environment marked so that inLimitedChild() is true there. Waits for
// its end and returns it. Throws vdg::Error when cpu_seconds is out of range or the child cannot
// be started.
ChildOutcome runLimitedChild(const ProcessLimits& limits, const std::vector<std::string>& args);

// This program's own arguments (/proc/self/cmdline), for runLimitedChild.
std::vector<std::string> thisProgramArguments();

// Whether this process is a limited child (runLimitedChild). The first call takes the mark out of
// the environment; later calls give the same answer.
bool inLimitedChild();

// In the limited child: sets the CPU and address-space limits back to this program's parent's
// (the limited phase is over) and closes the announcement channel. Nothing elsewhere.
void liftLimits();

// In the limited child, before liftLimits: tells the parent that `path` was created
// (ChildOutcome::created). Nothing elsewhere.
void announceCreated(const std::string& path);

}  // namespace vdg::script
