// The script's child process (child_process.h): the same program executed again under resource
// limits, waiting for it with signals forwarded, and the channel through which it names the files
// it made.
#include "vdg/script/child_process.h"

#include <fcntl.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>

#include "vdg/geom/error.h"

#if defined(__SANITIZE_ADDRESS__)
#define VDG_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define VDG_ASAN 1
#endif
#endif

extern char** environ;

namespace vdg::script {
namespace {

// The environment variable that marks the child: "FD CPU_SOFT AS_SOFT" (the announcement pipe's
// write end, and the parent's soft limits, restored by liftLimits; "-1" for unlimited).
constexpr const char* kChildMark = "VDG_SCRIPT_CHILD";

struct ChildState {
  bool child = false;
  int announce = -1;
  long long cpu_before = -1, as_before = -1;
};

ChildState& childState() {
  static ChildState state = [] {
    ChildState s;
    const char* mark = std::getenv(kChildMark);
    if (mark && std::sscanf(mark, "%d %lld %lld", &s.announce, &s.cpu_before, &s.as_before) == 3) s.child = true;
    if (mark) ::unsetenv(kChildMark);
    return s;
  }();
  return state;
}

// Parent side: the child signals are forwarded to.
volatile pid_t g_child = 0;

void forward(int sig) {
  if (g_child > 0) ::kill(g_child, sig);
}

constexpr int kForwarded[] = {SIGINT, SIGTERM, SIGHUP, SIGQUIT};

#ifndef VDG_ASAN
// The address space in use now (bytes; /proc/self/statm), 0 when unknown.
std::size_t addressSpaceNow() {
  std::FILE* f = std::fopen("/proc/self/statm", "re");
  if (!f) return 0;
  unsigned long pages = 0;
  const bool ok = std::fscanf(f, "%lu", &pages) == 1;
  std::fclose(f);
  return ok ? pages * static_cast<std::size_t>(::sysconf(_SC_PAGESIZE)) : 0;
}
#endif

long long softText(rlim_t value) { return value == RLIM_INFINITY ? -1 : static_cast<long long>(value); }

// Everything the child needs between fork and exec, made before the fork (no allocation there).
struct Launch {
  std::vector<std::string> args, env;
  std::vector<char*> argv, envp;
  struct rlimit cpu {
  }, as{};
  bool limit_as = false;
};

Launch prepare(const ProcessLimits& limits, const std::vector<std::string>& args, int announce) {
  Launch l;
  l.args = args;
  struct rlimit cpu_now {
  }, as_now{};
  ::getrlimit(RLIMIT_CPU, &cpu_now);
  ::getrlimit(RLIMIT_AS, &as_now);
  l.cpu = cpu_now;
  l.cpu.rlim_cur = static_cast<rlim_t>(limits.cpu_seconds);
  if (cpu_now.rlim_max != RLIM_INFINITY && l.cpu.rlim_cur > cpu_now.rlim_max) l.cpu.rlim_cur = cpu_now.rlim_max;
#ifndef VDG_ASAN
  if (limits.address_space > 0) {
    l.as = as_now;
    const rlim_t want = static_cast<rlim_t>(addressSpaceNow() + limits.address_space);
    if (as_now.rlim_cur == RLIM_INFINITY || want < as_now.rlim_cur) l.as.rlim_cur = want;
    l.limit_as = true;
  }
#endif
  for (char** e = environ; e && *e; ++e)
    if (std::strncmp(*e, kChildMark, std::strlen(kChildMark)) != 0) l.env.emplace_back(*e);
#ifdef VDG_ASAN
  // Under the sanitizers the child skips LeakSanitizer's exit check: its StopTheWorld tracer dies
  // of SIGSEGV in this limited child ("Tracer caught signal 11", depending on the memory layout,
  // e.g. the length of the working folder's path), which fails the run after the script ended
  // well. The parent's check and the in-process script tests (tests/script) still look for leaks.
  std::string lsan = "LSAN_OPTIONS=";
  for (auto it = l.env.begin(); it != l.env.end(); ++it)
    if (it->rfind(lsan, 0) == 0) {
      lsan = *it + ":";
      l.env.erase(it);
      break;
    }
  l.env.push_back(lsan + "detect_leaks=0");
#endif
  l.env.push_back(std::string(kChildMark) + "=" + std::to_string(announce) + " " +
                  std::to_string(softText(cpu_now.rlim_cur)) + " " + std::to_string(softText(as_now.rlim_cur)));
  for (std::string& a : l.args) l.argv.push_back(a.data());
  l.argv.push_back(nullptr);
  for (std::string& e : l.env) l.envp.push_back(e.data());
  l.envp.push_back(nullptr);
  return l;
}

// In the forked child, before exec: async-signal-safe calls only.
[[noreturn]] void execLimited(const Launch& l, int announce, pid_t parent) {
  ::prctl(PR_SET_PDEATHSIG, SIGKILL);
  if (::getppid() != parent) ::_exit(127);  // the parent died before the line above
  ::fcntl(announce, F_SETFD, 0);            // kept across exec
  ::setrlimit(RLIMIT_CPU, &l.cpu);
  const struct rlimit no_core { 0, 0 };
  ::setrlimit(RLIMIT_CORE, &no_core);
  if (l.limit_as) ::setrlimit(RLIMIT_AS, &l.as);
  ::execve("/proc/self/exe", l.argv.data(), l.envp.data());
  constexpr char kFailed[] = "vdg: error: cannot start the script's process (/proc/self/exe)\n";
  if (::write(2, kFailed, sizeof kFailed - 1) < 0) ::_exit(1);
  ::_exit(1);
}

// Reads the child's announcements (NUL-terminated paths) until it closes the pipe.
void readAnnouncements(int fd, std::vector<std::string>& created) {
  std::string pending;
  char buffer[4096];
  for (;;) {
    const ssize_t n = ::read(fd, buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    pending.append(buffer, static_cast<std::size_t>(n));
    for (std::size_t end; (end = pending.find('\0')) != std::string::npos;) {
      created.push_back(pending.substr(0, end));
      pending.erase(0, end + 1);
    }
  }
}

ChildOutcome waitForChild(pid_t pid, int announce, const ProcessLimits& limits) {
  ChildOutcome out;
  struct sigaction forwarding {
  }, before[4];
  forwarding.sa_handler = forward;
  sigemptyset(&forwarding.sa_mask);
  g_child = pid;
  for (int i = 0; i < 4; ++i) ::sigaction(kForwarded[i], &forwarding, &before[i]);
  readAnnouncements(announce, out.created);
  ::close(announce);
  int status = 0;
  struct rusage usage {};
  while (::wait4(pid, &status, 0, &usage) < 0 && errno == EINTR) {
  }
  g_child = 0;
  for (int i = 0; i < 4; ++i) ::sigaction(kForwarded[i], &before[i], nullptr);
  out.cpu_seconds = static_cast<double>(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
                    static_cast<double>(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec) * 1e-6;
  if (WIFEXITED(status)) {
    out.end = ChildEnd::kExited;
    out.code = WEXITSTATUS(status);
  } else {
    out.code = WIFSIGNALED(status) ? WTERMSIG(status) : SIGKILL;
    const bool spent = out.code == SIGXCPU || (out.code == SIGKILL && out.cpu_seconds >= limits.cpu_seconds);
    out.end = spent ? ChildEnd::kCpuExceeded : ChildEnd::kSignaled;
  }
  return out;
}

}  // namespace

ChildOutcome runLimitedChild(const ProcessLimits& limits, const std::vector<std::string>& args) {
  if (limits.cpu_seconds < 1 || limits.cpu_seconds > kMaxCpuSeconds)
    throw Error("the CPU-time limit must be 1 to " + std::to_string(kMaxCpuSeconds) + " seconds, got " +
                std::to_string(limits.cpu_seconds));
  if (args.empty()) throw Error("cannot start the script's process: no arguments");
  int pipe_fds[2];
  if (::pipe2(pipe_fds, O_CLOEXEC) != 0)
    throw Error(std::string("cannot start the script's process: ") + std::strerror(errno));
  const Launch launch = prepare(limits, args, pipe_fds[1]);
  std::fflush(nullptr);
  const pid_t parent = ::getpid();
  const pid_t pid = ::fork();
  if (pid == 0) execLimited(launch, pipe_fds[1], parent);
  const int err = errno;
  ::close(pipe_fds[1]);
  if (pid < 0) {
    ::close(pipe_fds[0]);
    throw Error(std::string("cannot start the script's process: ") + std::strerror(err));
  }
  return waitForChild(pid, pipe_fds[0], limits);
}

std::vector<std::string> thisProgramArguments() {
  std::ifstream in("/proc/self/cmdline", std::ios::binary);
  const std::string all((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::vector<std::string> args;
  std::size_t start = 0;
  while (start < all.size()) {
    const std::size_t end = all.find('\0', start);
    args.push_back(all.substr(start, end == std::string::npos ? std::string::npos : end - start));
    if (end == std::string::npos) break;
    start = end + 1;
  }
  return args;
}

bool inLimitedChild() { return childState().child; }

void liftLimits() {
  ChildState& s = childState();
  if (!s.child) return;
  struct rlimit cpu {
  }, as{};
  ::getrlimit(RLIMIT_CPU, &cpu);
  ::getrlimit(RLIMIT_AS, &as);
  cpu.rlim_cur = s.cpu_before < 0 ? cpu.rlim_max : static_cast<rlim_t>(s.cpu_before);
  as.rlim_cur = s.as_before < 0 ? as.rlim_max : static_cast<rlim_t>(s.as_before);
  ::setrlimit(RLIMIT_CPU, &cpu);
  ::setrlimit(RLIMIT_AS, &as);
  if (s.announce >= 0) ::close(s.announce);
  s.announce = -1;
}

void announceCreated(const std::string& path) {
  const ChildState& s = childState();
  if (!s.child || s.announce < 0) return;
  const std::string message = path + '\0';
  std::size_t done = 0;
  while (done < message.size()) {
    const ssize_t n = ::write(s.announce, message.data() + done, message.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return;
    done += static_cast<std::size_t>(n);
  }
}

}  // namespace vdg::script
