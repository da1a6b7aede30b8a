#include "video.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <climits>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

#include "cli.h"
#include "vdg/geom/error.h"
#include "vdg/io/atomic_file.h"

namespace vdg::cli {
namespace {

namespace fs = std::filesystem;

// A fresh empty file beside `real` with the extension of `video` (ffmpeg picks the format from
// it), carrying the mode the target has, or would get as a new file. Its name is registered for
// removal on an interrupt BEFORE the file is created (O_EXCL), as StagedFile does: an interrupt
// between the two would otherwise leave it behind. Returns the name; `token` is keepOnInterrupt's.
std::string makeTemporaryBeside(const std::string& real, const std::string& where, const std::string& video,
                                int& token) {
  constexpr int kAttempts = 16;
  const std::string ext = fs::path(video).extension().string();
  const mode_t mask = ::umask(0);  // the tool is single-threaded here: read the umask and put it back
  ::umask(mask);
  struct stat existing {};
  const mode_t mode = ::stat(real.c_str(), &existing) == 0 ? existing.st_mode & 07777 : 0666 & ~mask;
  for (int attempt = 0; attempt < kAttempts; ++attempt) {
    const std::string name = temporaryPathFor(real) + ext;
    token = removeOnInterrupt(name);
    const int fd = ::open(name.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0600);
    if (fd >= 0) {
      (void)::fchmod(fd, mode);
      ::close(fd);
      return name;
    }
    const int err = errno;
    keepOnInterrupt(token);  // not ours: never remove it
    token = -1;
    if (err != EEXIST) throw Error(where + ": cannot write file: " + std::strerror(err));
  }
  throw Error(where + ": cannot write file: no free temporary name beside it");
}

// What became of one ffmpeg run.
struct FfmpegRun {
  bool timed_out = false, interrupted = false;
  int status = 0;         // waitpid's status (when neither timed out nor interrupted)
  std::string last_line;  // the last non-empty line ffmpeg wrote to stderr, made printable
};

constexpr std::size_t kKeptStderrBytes = 65536;  // of ffmpeg's stderr, the tail kept for its last line
constexpr std::size_t kShownLineBytes = 300;     // of that line, what the message shows

// The last non-empty line of `text`, control characters made spaces, trimmed, at most
// kShownLineBytes bytes.
std::string lastLine(const std::string& text) {
  std::string line;
  std::size_t end = text.size();
  while (end > 0 && line.empty()) {
    const std::size_t start = text.rfind('\n', end - 1);
    const std::size_t from = start == std::string::npos ? 0 : start + 1;
    line = text.substr(from, end - from);
    for (char& c : line)
      if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = ' ';
    const auto first = line.find_first_not_of(' ');
    line = first == std::string::npos ? "" : line.substr(first, line.find_last_not_of(' ') - first + 1);
    end = from == 0 ? 0 : from - 1;
  }
  if (line.size() > kShownLineBytes) line = line.substr(0, kShownLineBytes) + "...";
  return line;
}

// The child: its own process group (so that a timeout kills whatever it started too), stdin and
// stdout /dev/null, stderr the pipe; then ffmpeg from PATH. Only async-signal-safe calls.
[[noreturn]] void execFfmpeg(char* const* argv, int err_w) {
  ::setpgid(0, 0);
  const int devnull = ::open("/dev/null", O_RDWR);
  if (devnull >= 0) {
    ::dup2(devnull, STDIN_FILENO);
    ::dup2(devnull, STDOUT_FILENO);
  }
  ::dup2(err_w, STDERR_FILENO);
  ::execvp("ffmpeg", argv);
  static const char msg[] = "cannot run ffmpeg\n";
  (void)!::write(STDERR_FILENO, msg, sizeof msg - 1);
  ::_exit(127);
}

// Reads the child's stderr until it closes or the deadline passes; then reaps the child, killing
// its process group first when the deadline passed or a signal interrupted the wait.
FfmpegRun superviseFfmpeg(pid_t pid, int err_r, std::chrono::steady_clock::time_point deadline) {
  using Clock = std::chrono::steady_clock;
  FfmpegRun run;
  std::string text;
  const auto remainingMs = [&] {
    return std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now()).count();
  };
  for (bool open = true; open;) {
    const long long left = remainingMs();
    if (left <= 0) {
      run.timed_out = true;
      break;
    }
    pollfd p{err_r, POLLIN, 0};
    const int r = ::poll(&p, 1, static_cast<int>(std::min<long long>(left, INT_MAX)));
    if (r < 0 && errno == EINTR) {
      run.interrupted = true;
      break;
    }
    if (r <= 0) continue;
    char buffer[4096];
    const ssize_t n = ::read(err_r, buffer, sizeof buffer);
    if (n > 0) {
      text.append(buffer, static_cast<std::size_t>(n));
      if (text.size() > 2 * kKeptStderrBytes) text.erase(0, text.size() - kKeptStderrBytes);
    } else if (n == 0 || (errno != EINTR && errno != EAGAIN)) {
      open = false;
    }
  }
  // stderr closed: the child is exiting (or left a grandchild holding the pipe); wait for it
  // within what is left of the time.
  while (!run.timed_out && !run.interrupted) {
    const pid_t done = ::waitpid(pid, &run.status, WNOHANG);
    if (done == pid || (done < 0 && errno != EINTR)) break;
    if (remainingMs() <= 0)
      run.timed_out = true;
    else
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  if (run.timed_out || run.interrupted) {
    ::kill(-pid, SIGKILL);
    ::kill(pid, SIGKILL);
    while (::waitpid(pid, &run.status, 0) < 0 && errno == EINTR) {
    }
  }
  ::close(err_r);
  run.last_line = lastLine(text);
  return run;
}

// Runs ffmpeg with `args` (argv[1...]) for at most `seconds`.
FfmpegRun runFfmpeg(const std::vector<std::string>& args, double seconds, const std::string& where) {
  std::vector<std::string> words{"ffmpeg"};
  words.insert(words.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (std::string& w : words) argv.push_back(w.data());
  argv.push_back(nullptr);
  int err[2];
  if (::pipe2(err, O_CLOEXEC) != 0) throw Error(where + ": cannot run ffmpeg: " + std::strerror(errno));
  const auto deadline = std::chrono::steady_clock::now() +
                        std::chrono::milliseconds(static_cast<long long>(std::min(seconds, 1e9) * 1000.0));
  const pid_t pid = ::fork();
  if (pid < 0) {
    const int e = errno;
    ::close(err[0]);
    ::close(err[1]);
    throw Error(where + ": cannot run ffmpeg: " + std::strerror(e));
  }
  if (pid == 0) execFfmpeg(argv.data(), err[1]);
  ::setpgid(pid, pid);   // also here, so that the group exists before any kill (either call may win)
  killOnInterrupt(pid);  // Ctrl-C reaches vdg only: its handler stops the encoder too
  ::close(err[1]);
  FfmpegRun run = superviseFfmpeg(pid, err[0], deadline);
  killOnInterrupt(0);
  return run;
}

// The one-line message for a run that did not succeed; empty when it did.
std::string failureOf(const FfmpegRun& run, double seconds, const std::string& frames_dir) {
  if (run.interrupted) return "interrupted; ffmpeg was stopped (the frames are in " + frames_dir + ")";
  if (run.timed_out)
    return "ffmpeg did not finish within " + numberText(seconds) + " s and was stopped (the frames are in " +
           frames_dir + "; VDG_FFMPEG_TIMEOUT sets the seconds)";
  if (WIFEXITED(run.status) && WEXITSTATUS(run.status) == 0) return "";
  const std::string how = WIFEXITED(run.status)     ? "exit status " + std::to_string(WEXITSTATUS(run.status))
                          : WIFSIGNALED(run.status) ? "killed by signal " + std::to_string(WTERMSIG(run.status))
                                                    : "status " + std::to_string(run.status);
  return "ffmpeg failed (" + how + ")" + (run.last_line.empty() ? "" : ": " + run.last_line) + " (the frames are in " +
         frames_dir + ")";
}

}  // namespace

double ffmpegTimeoutSeconds(long frame_count) {
  if (const char* env = std::getenv("VDG_FFMPEG_TIMEOUT"); env != nullptr) {
    char* end = nullptr;
    const double v = std::strtod(env, &end);
    if (end == env || *end != '\0' || !std::isfinite(v) || !(v > 0) || v > 1e9)
      throw Error("VDG_FFMPEG_TIMEOUT: expected a number of seconds > 0, got " + quotedText(env));
    return v;
  }
  return kFfmpegBaseSeconds + kFfmpegSecondsPerFrame * static_cast<double>(std::max(0L, frame_count));
}

bool isVideoPath(std::string_view path) { return hasExtension(path, ".mp4") || hasExtension(path, ".gif"); }

void requireFfmpeg(const std::string& where, const std::string& instead) {
  (void)ffmpegTimeoutSeconds(0);  // a bad VDG_FFMPEG_TIMEOUT is refused before any frame is made
  if (!findOnPath("ffmpeg"))
    throw Error(where + ": writing a video needs the 'ffmpeg' program, which is not on PATH; install it, or " +
                instead);
}

void encodeVideo(const std::string& where, const std::string& video, const VideoFrames& frames) {
  const std::string real = checkedOutputPath(video);  // never through a link that leaves the folder
  struct stat existing {};
  if (::stat(real.c_str(), &existing) == 0 && !S_ISREG(existing.st_mode))
    throw Error(where + ": is not a regular file; a video is written only to a file");
  int token = -1;
  const std::string temp = makeTemporaryBeside(real, where, video, token);
  struct Forget {  // the temp file is the interrupt handler's to remove until this call ends
    int token;
    ~Forget() { keepOnInterrupt(token); }
  } const forget{token};
  const double seconds = ffmpegTimeoutSeconds(frames.count);
  std::vector<std::string> args{"-loglevel",
                                "error",
                                "-y",
                                "-framerate",
                                "24",
                                "-start_number",
                                std::to_string(frames.first),
                                "-i",
                                (fs::path(frames.dir) / "frame_%04d.png").string(),
                                "-frames:v",
                                std::to_string(frames.count)};
  if (hasExtension(video, ".gif"))
    args.insert(args.end(), {"-vf", "split[a][b];[a]palettegen[p];[b][p]paletteuse"});
  else
    args.insert(args.end(), {"-c:v", "libx264", "-pix_fmt", "yuv420p", "-vf", "pad=ceil(iw/2)*2:ceil(ih/2)*2"});
  args.push_back(temp);
  std::error_code ec;
  std::string failure;
  try {
    failure = failureOf(runFfmpeg(args, seconds, where), seconds, frames.dir);
  } catch (...) {
    fs::remove(temp, ec);
    keepNewOutputs();  // the frames stay for the user
    throw;
  }
  if (!failure.empty()) {
    fs::remove(temp, ec);
    keepNewOutputs();  // the frames stay for the user, as the message says
    throw Error(where + ": " + failure);
  }
  if (::rename(temp.c_str(), real.c_str()) != 0) {
    const int err = errno;
    fs::remove(temp, ec);
    throw Error(where + ": cannot write file: " + std::strerror(err));
  }
}

}  // namespace vdg::cli
