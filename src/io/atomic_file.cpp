#include "vdg/io/atomic_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cassert>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <random>
#include <sstream>

#include "vdg/geom/error.h"

namespace vdg {
namespace {

namespace fs = std::filesystem;

constexpr int kMaxLinks = 40;     // as Linux's own limit on links followed in one path
constexpr int kMaxAttempts = 64;  // temporary names tried before giving up

std::string errnoText(int err) { return std::strerror(err); }

[[noreturn]] void failWrite(const std::string& path, int err) {
  throw Error(path + ": cannot write file: " + errnoText(err));
}

// What a path names, for messages about files vdg will not write.
std::string kindOf(mode_t mode) {
  if (S_ISDIR(mode)) return "a folder";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISFIFO(mode)) return "a FIFO";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

// Writes all of `data` to `fd`, retrying short writes and interrupted calls. Returns 0 or errno.
int writeAll(int fd, std::string_view data) {
  std::size_t done = 0;
  while (done < data.size()) {
    const ssize_t n = ::write(fd, data.data() + done, data.size() - done);
    if (n < 0) {
      if (errno == EINTR) continue;
      return errno;
    }
    if (n == 0) return EIO;  // no progress on a regular file or device: give up rather than spin
    done += static_cast<std::size_t>(n);
  }
  return 0;
}

std::string randomSuffix() {
  static constexpr char kChars[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789";
  static std::atomic<unsigned> counter{0};
  thread_local std::mt19937_64 rng{std::random_device{}() ^ (static_cast<std::uint64_t>(::getpid()) << 20) ^
                                   counter.fetch_add(1)};
  std::string s(6, 'x');
  for (char& c : s) c = kChars[rng() % (sizeof(kChars) - 1)];
  return s;
}

// Flushes a folder's entries (a rename) to the disk; best effort, as not every file system can.
void syncFolder(const std::string& folder) {
  const int fd = ::open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) return;
  (void)::fsync(fd);
  ::close(fd);
}

std::string folderOf(const std::string& path) {
  const fs::path parent = fs::path(path).parent_path();
  return parent.empty() ? std::string(".") : parent.string();
}

// Writes to a character device or a FIFO in place.
void writeStream(const std::string& path, const std::string& real, bool fifo, std::string_view contents) {
  const int fd = ::open(real.c_str(), O_WRONLY | O_NOCTTY | O_CLOEXEC | O_NONBLOCK);
  if (fd < 0) {
    if (fifo && errno == ENXIO) throw Error(path + ": is a FIFO that no program is reading");
    failWrite(path, errno);
  }
  struct stat st {};
  if (::fstat(fd, &st) != 0 || !(S_ISCHR(st.st_mode) || S_ISFIFO(st.st_mode))) {
    ::close(fd);
    throw Error(path + ": changed while being opened; not written");
  }
  // Blocking writes from here on: a FIFO's reader may be slower than vdg.
  const int flags = ::fcntl(fd, F_GETFL);
  if (flags >= 0) (void)::fcntl(fd, F_SETFL, flags & ~O_NONBLOCK);
  int err = writeAll(fd, contents);
  if (::close(fd) != 0 && err == 0 && errno != EINTR) err = errno;
  if (err != 0) failWrite(path, err);
}

}  // namespace

std::string resolveOutputPath(const std::string& path) {
  std::string current = path;
  for (int hops = 0;; ++hops) {
    struct stat st {};
    if (::lstat(current.c_str(), &st) != 0 || !S_ISLNK(st.st_mode)) return current;
    if (hops == kMaxLinks) throw Error(path + ": too many levels of symbolic links");
    std::string link(4096, '\0');
    const ssize_t n = ::readlink(current.c_str(), link.data(), link.size());
    if (n < 0 || static_cast<std::size_t>(n) >= link.size()) failWrite(path, n < 0 ? errno : ENAMETOOLONG);
    link.resize(static_cast<std::size_t>(n));
    const fs::path target(link);
    current = target.is_absolute() ? link : (fs::path(current).parent_path() / target).string();
  }
}

std::string temporaryPathFor(const std::string& real_target) {
  return (fs::path(folderOf(real_target)) / (".vdg-" + randomSuffix())).string();
}

StagedFile::StagedFile(const std::string& path, std::string_view contents, const std::string& temp_path)
    : path_(path), target_(resolveOutputPath(path)) {
  struct stat st {};
  bool replacing = false;
  if (::stat(target_.c_str(), &st) == 0) {
    if (!S_ISREG(st.st_mode)) throw Error(path_ + ": is " + kindOf(st.st_mode) + ", not a file vdg can replace");
    replacing = true;
  }
  const std::string folder = folderOf(target_);
  int fd = -1;
  const int attempts = temp_path.empty() ? kMaxAttempts : 1;
  for (int attempt = 0; attempt < attempts && fd < 0; ++attempt) {
    temp_path_ = temp_path.empty() ? temporaryPathFor(target_) : temp_path;
    // 0666 here: the kernel applies the umask, as for any new file.
    fd = ::open(temp_path_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd < 0 && errno != EEXIST) {
      const int err = errno;
      temp_path_.clear();
      if (err == ENOENT) throw Error(path_ + ": cannot write file: the folder " + folder + " does not exist");
      failWrite(path_, err);
    }
  }
  if (fd < 0) {
    temp_path_.clear();
    failWrite(path_, EEXIST);
  }
  int err = 0;
  if (replacing) (void)::fchmod(fd, st.st_mode & 07777);  // best effort: set-id bits may be refused
  err = writeAll(fd, contents);
  if (err == 0 && ::fsync(fd) != 0) err = errno;
  if (::close(fd) != 0 && err == 0 && errno != EINTR) err = errno;
  if (err != 0) {
    ::unlink(temp_path_.c_str());
    temp_path_.clear();
    failWrite(path_, err);
  }
}

StagedFile::StagedFile(StagedFile&& other) noexcept
    : path_(std::move(other.path_)), target_(std::move(other.target_)), temp_path_(std::move(other.temp_path_)) {
  other.temp_path_.clear();
}

StagedFile::~StagedFile() {
  if (!temp_path_.empty()) ::unlink(temp_path_.c_str());
}

void StagedFile::commit() {
  assert(!temp_path_.empty() && "StagedFile committed twice");
  if (::rename(temp_path_.c_str(), target_.c_str()) != 0) {
    const int err = errno;
    ::unlink(temp_path_.c_str());
    temp_path_.clear();
    if (err == EISDIR || err == ENOTDIR) throw Error(path_ + ": is a folder, not a file vdg can replace");
    failWrite(path_, err);
  }
  temp_path_.clear();
  syncFolder(folderOf(target_));
}

std::string StagedFile::release() {
  std::string temp = std::move(temp_path_);
  temp_path_.clear();
  return temp;
}

void writeFileAtomically(const std::string& path, std::string_view contents) {
  const std::string real = resolveOutputPath(path);
  struct stat st {};
  if (::stat(real.c_str(), &st) == 0) {
    if (S_ISCHR(st.st_mode) || S_ISFIFO(st.st_mode)) return writeStream(path, real, S_ISFIFO(st.st_mode), contents);
    if (!S_ISREG(st.st_mode)) throw Error(path + ": is " + kindOf(st.st_mode) + ", not a file");
  }
  StagedFile staged(path, contents);
  staged.commit();
}

void writeFileAtomically(const std::string& path, const std::function<void(std::ostream&)>& write) {
  std::ostringstream out;
  write(out);
  if (!out) throw Error(path + ": cannot write file: out of memory while formatting it");
  writeFileAtomically(path, std::string_view(out.view()));
}

}  // namespace vdg
