#include "vdg/io/read_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <climits>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <mutex>

#include "path_facts.h"
#include "vdg/geom/error.h"

namespace vdg {
namespace {

// "a model", "an edit script".
std::string withArticle(const std::string& noun) {
  const bool vowel = !noun.empty() && std::string("aeiouAEIOU").find(noun[0]) != std::string::npos;
  return (vowel ? "an " : "a ") + noun;
}

std::string sizeText(std::size_t bytes) {
  if (bytes >= (std::size_t{1} << 20)) return std::to_string(bytes >> 20) + " MiB";
  return std::to_string(bytes) + " bytes";
}

// The read root (ScopedReadRoot): a real path, or empty.
std::mutex g_root_mutex;
std::string g_root;

std::string readRoot() {
  const std::lock_guard<std::mutex> lock(g_root_mutex);
  return g_root;
}

// The real path of what `fd` (opened from `path`) is: /proc/self/fd/FD where /proc is mounted;
// otherwise realpath(path), kept only when it is the same file as the descriptor's. Empty when
// neither gives an answer.
std::string openedRealPath(int fd, const std::string& path) {
  char link[64];
  std::snprintf(link, sizeof link, "/proc/self/fd/%d", fd);
  char target[PATH_MAX + 1];
  const ssize_t n = ::readlink(link, target, PATH_MAX);
  if (n > 0 && target[0] == '/') return std::string(target, static_cast<std::size_t>(n));
  struct stat opened {
  }, named{};
  char* real = ::realpath(path.c_str(), nullptr);
  if (!real) return {};
  std::string result(real);
  std::free(real);
  if (::fstat(fd, &opened) != 0 || ::stat(result.c_str(), &named) != 0 || opened.st_dev != named.st_dev ||
      opened.st_ino != named.st_ino)
    return {};
  return result;
}

bool isBelow(const std::string& real, const std::string& folder) {
  if (folder == "/") return !real.empty() && real[0] == '/';
  return real.size() > folder.size() && real.compare(0, folder.size(), folder) == 0 && real[folder.size()] == '/';
}

// Opens `path` for reading without blocking on a FIFO and checks, on the open descriptor, that it
// is a regular file and lies below the read root (so neither check can be raced by swapping the file).
int openRegular(const std::string& path, const std::string& what, struct stat& info) {
  if (path.empty()) throw Error("empty file name given for the " + what);
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_NOCTTY | O_CLOEXEC);
  if (fd < 0) {
    const int err = errno;
    if (err == ENOENT) throw Error(path + ": no such file (" + what + ")");
    if (err == EISDIR) throw Error(path + ": is a folder, not " + withArticle(what) + " file");
    throw Error(path + ": cannot open " + what + ": " + std::strerror(err));
  }
  if (::fstat(fd, &info) != 0 || !S_ISREG(info.st_mode)) {
    const std::string kind = S_ISREG(info.st_mode) ? "cannot be examined" : "is " + detail::fileKindText(info.st_mode);
    ::close(fd);
    throw Error(path + ": " + kind + ", not " + withArticle(what) + " file");
  }
  const std::string root = readRoot();
  if (!root.empty() && !isBelow(openedRealPath(fd, path), root)) {
    ::close(fd);
    throw ReadRootError(path + ": the " + what + " leads outside the read root '" + root + "'");
  }
  return fd;
}

}  // namespace

ScopedReadRoot::ScopedReadRoot(const std::string& root) {
  errno = 0;
  char* real = ::realpath(root.empty() ? "." : root.c_str(), nullptr);
  struct stat info {};
  if (!real || ::stat(real, &info) != 0 || !S_ISDIR(info.st_mode)) {
    const int err = errno ? errno : ENOTDIR;
    std::free(real);
    throw Error(root + ": the read root is not a folder" + (err ? std::string(": ") + std::strerror(err) : ""));
  }
  const std::lock_guard<std::mutex> lock(g_root_mutex);
  previous_ = g_root;
  g_root = real;
  std::free(real);
}

ScopedReadRoot::~ScopedReadRoot() {
  const std::lock_guard<std::mutex> lock(g_root_mutex);
  g_root = previous_;
}

std::string currentReadRoot() { return readRoot(); }

bool openedBelow(int fd, const std::string& path, const std::string& folder) {
  return isBelow(openedRealPath(fd, path), folder);
}

void checkInputFile(const std::string& path, const std::string& what) {
  struct stat info {};
  ::close(openRegular(path, what, info));
}

std::string readFileLimited(const std::string& path, const std::string& what, std::size_t max_bytes) {
  struct stat info {};
  const int fd = openRegular(path, what, info);
  const auto size = static_cast<std::size_t>(info.st_size);
  if (size > max_bytes) {
    ::close(fd);
    throw Error(path + ": " + what + " file is " + sizeText(size) + ", more than the limit of " + sizeText(max_bytes));
  }
  std::string text;
  try {
    text.resize(size);
  } catch (const std::bad_alloc&) {
    ::close(fd);
    throw Error(path + ": not enough memory to read " + sizeText(size));
  }
  std::size_t done = 0;
  while (done < size) {
    const ssize_t n = ::read(fd, text.data() + done, size - done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      const int err = errno;
      ::close(fd);
      throw Error(path + ": cannot read " + what + ": " + std::strerror(err));
    }
    if (n == 0) break;  // the file shrank while being read
    done += static_cast<std::size_t>(n);
  }
  ::close(fd);
  text.resize(done);
  return text;
}

}  // namespace vdg
