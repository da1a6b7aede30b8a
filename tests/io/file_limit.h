// Running code in a forked child under a file size limit (RLIMIT_FSIZE), which makes writes beyond
// the limit fail with EFBIG exactly as a full disk makes them fail with ENOSPC: a way to test the
// handling of failed writes without filling a disk.
#pragma once

#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "vdg/geom/error.h"

namespace vdg::testing {

// The file size limit the disk-full tests write under (bytes).
inline constexpr long kFileLimit = 4096;

// The names of every entry of `dir`, sorted: checks that no temporary file is left behind.
inline std::vector<std::string> entries(const std::filesystem::path& dir) {
  std::vector<std::string> names;
  for (const auto& e : std::filesystem::directory_iterator(dir)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

// Runs `f` in a child process whose files may not grow beyond `limit_bytes` (SIGXFSZ ignored, so a
// write past it fails with EFBIG). Returns the vdg::Error message `f` threw, "" when it returned
// normally, or "crashed"/"other exception" when it did neither.
inline std::string errorUnderFileLimit(long limit_bytes, const std::function<void()>& f) {
  int fds[2];
  if (::pipe(fds) != 0) return "pipe failed";
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::close(fds[0]);
    ::signal(SIGXFSZ, SIG_IGN);
    const rlimit limit{static_cast<rlim_t>(limit_bytes), static_cast<rlim_t>(limit_bytes)};
    ::setrlimit(RLIMIT_FSIZE, &limit);
    std::string message;
    int code = 0;
    try {
      f();
    } catch (const Error& e) {
      message = e.what();
    } catch (...) {
      code = 3;
    }
    if (::write(fds[1], message.data(), message.size()) != static_cast<ssize_t>(message.size())) code = 4;
    ::close(fds[1]);
    ::_exit(code);
  }
  ::close(fds[1]);
  std::string message;
  char buffer[512];
  for (ssize_t n; (n = ::read(fds[0], buffer, sizeof buffer)) > 0;) message.append(buffer, static_cast<std::size_t>(n));
  ::close(fds[0]);
  int status = 0;
  ::waitpid(pid, &status, 0);
  if (!WIFEXITED(status)) return "crashed";
  if (WEXITSTATUS(status) != 0) return "other exception";
  return message;
}

}  // namespace vdg::testing
