#include "vdg/io/read_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "vdg/geom/error.h"

namespace vdg {
namespace {

std::string kindOf(mode_t mode) {
  if (S_ISDIR(mode)) return "a folder";
  if (S_ISFIFO(mode)) return "a FIFO (named pipe)";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

// "a model", "an edit script".
std::string withArticle(const std::string& noun) {
  const bool vowel = !noun.empty() && std::string("aeiouAEIOU").find(noun[0]) != std::string::npos;
  return (vowel ? "an " : "a ") + noun;
}

std::string sizeText(std::size_t bytes) {
  if (bytes >= (std::size_t{1} << 20)) return std::to_string(bytes >> 20) + " MiB";
  return std::to_string(bytes) + " bytes";
}

// Opens `path` for reading without blocking on a FIFO and checks, on the open descriptor, that it
// is a regular file (so the check cannot be raced by swapping the file).
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
    const std::string kind = S_ISREG(info.st_mode) ? "cannot be examined" : "is " + kindOf(info.st_mode);
    ::close(fd);
    throw Error(path + ": " + kind + ", not " + withArticle(what) + " file");
  }
  return fd;
}

}  // namespace

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
