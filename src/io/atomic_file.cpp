#include "vdg/io/atomic_file.h"

#include <dirent.h>
#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cassert>
#include <cctype>
#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <random>
#include <set>
#include <sstream>
#include <vector>

#include "path_facts.h"
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

// ---- What an interrupt removes: fixed slots, read by the signal handler (async-signal-safe) ----
// A slot's state: 0 free, 1 being filled or emptied, 2 a file to unlink, 3 a folder to rmdir.
constexpr int kSlots = 64;
constexpr std::size_t kSlotPathMax = 4096;
struct Slot {
  std::atomic<int> state{0};
  char path[kSlotPathMax];
};
Slot g_slots[kSlots];    // files: registered while written
Slot g_folders[kSlots];  // folders made by makeOutputFolder, in the order made (parents first)
std::atomic<int> g_folder_count{0};

std::string absoluteText(const std::string& path) {
  std::error_code ec;
  const fs::path a = fs::absolute(path, ec);
  return ec ? path : a.lexically_normal().string();
}

// Files this run created (renamed into place where nothing was), newest first: a lock-free list
// that only grows, so that the signal handler can walk it. A file is removed only while it is
// still the one written (the same device and inode).
struct Created {
  dev_t device;
  ino_t inode;
  std::string path;  // absolute
  Created* next;
};
std::atomic<Created*> g_created{nullptr};
std::atomic<bool> g_keep_created{false};

void noteCreated(const std::string& path, dev_t device, ino_t inode) {
  auto* c = new Created{device, inode, absoluteText(path), g_created.load(std::memory_order_relaxed)};
  while (!g_created.compare_exchange_weak(c->next, c, std::memory_order_release, std::memory_order_relaxed)) {
  }
}

// Removes the files and then the (empty) folders this run made; async-signal-safe.
void removeNew() {
  if (!g_keep_created.load())
    for (const Created* c = g_created.load(std::memory_order_acquire); c; c = c->next) {
      struct stat st {};
      if (::lstat(c->path.c_str(), &st) == 0 && S_ISREG(st.st_mode) && st.st_dev == c->device && st.st_ino == c->inode)
        ::unlink(c->path.c_str());
    }
  for (int i = g_folder_count.load() - 1; i >= 0; --i)
    if (g_folders[i].state.load() == 3) ::rmdir(g_folders[i].path);  // only an empty folder goes
}

// Claims a free slot of `slots` for `path` in `state`; -1 when all are taken or the path too long.
int claimSlot(Slot* slots, const std::string& path, int state) {
  if (path.size() >= kSlotPathMax) return -1;
  for (int i = 0; i < kSlots; ++i) {
    int expected = 0;
    if (!slots[i].state.compare_exchange_strong(expected, 1)) continue;
    std::memcpy(slots[i].path, path.c_str(), path.size() + 1);
    slots[i].state.store(state);
    return i;
  }
  return -1;
}

std::atomic<pid_t> g_child_group{0};  // killOnInterrupt

extern "C" void onInterrupt(int sig) {
  if (const pid_t group = g_child_group.load(); group > 0) ::kill(-group, SIGKILL);  // it stops writing first
  for (Slot& slot : g_slots)
    if (slot.state.load() == 2) ::unlink(slot.path);
  removeNew();
  static constexpr char kInt[] = "vdg: interrupted (SIGINT); the files being written were removed\n";
  static constexpr char kTerm[] = "vdg: interrupted (SIGTERM); the files being written were removed\n";
  static constexpr char kHup[] = "vdg: interrupted (SIGHUP); the files being written were removed\n";
  const char* text = sig == SIGINT ? kInt : sig == SIGTERM ? kTerm : kHup;
  const std::size_t size = sig == SIGINT ? sizeof kInt : sig == SIGTERM ? sizeof kTerm : sizeof kHup;
  (void)!::write(STDERR_FILENO, text, size - 1);
  ::_exit(128 + sig);
}

// ---- Leftovers of killed runs ----------------------------------------------------------------

// 64-bit FNV-1a, to fold the identity of this boot, host, namespace and user into a short tag.
std::uint64_t fnv1a(std::string_view text, std::uint64_t h = 14695981039346656037ull) {
  for (unsigned char c : text) h = (h ^ c) * 1099511628211ull;
  return h;
}

// 12 hexadecimal digits identifying this boot of this host, its pid namespace and the user; empty
// when the boot id cannot be read (then no leftover can be proven ours, and none is removed).
const std::string& instanceTag() {
  static const std::string tag = [] {
    std::string boot;
    std::ifstream("/proc/sys/kernel/random/boot_id") >> boot;
    if (boot.size() < 16) return std::string();
    char host[256] = {};
    (void)::gethostname(host, sizeof host - 1);
    struct stat ns {};
    const std::string pidns = ::stat("/proc/self/ns/pid", &ns) == 0 ? std::to_string(ns.st_ino) : "?";
    const std::uint64_t h = fnv1a(boot + "|" + host + "|" + pidns + "|" + std::to_string(::geteuid()));
    char text[16];
    std::snprintf(text, sizeof text, "%012llx", static_cast<unsigned long long>(h & 0xffffffffffffull));
    return std::string(text);
  }();
  return tag;
}

// The writer's pid when `name` is ".vdg-RRRRRR-PID-TAG" with this instance's TAG, else 0.
long leftoverPid(std::string_view name, const std::string& tag) {
  if (tag.empty() || !name.starts_with(".vdg-") || name.size() < 5 + 6 + 1 + 1 + 1 + tag.size()) return 0;
  if (!name.ends_with("-" + tag)) return 0;
  for (char c : name.substr(5, 6))
    if (!std::isalnum(static_cast<unsigned char>(c))) return 0;
  if (name[11] != '-') return 0;
  const std::string_view digits = name.substr(12, name.size() - 12 - 1 - tag.size());
  if (digits.empty() || digits.size() > 9 || digits.front() == '0') return 0;
  long pid = 0;
  for (char c : digits) {
    if (c < '0' || c > '9') return 0;
    pid = pid * 10 + (c - '0');
  }
  return pid;
}

// Removes the proven leftovers of killed vdg runs in `folder` (see the header), once per folder
// and run.
void removeLeftovers(const std::string& folder) {
  static std::mutex mutex;
  static std::set<std::string> done;
  const std::string& tag = instanceTag();
  if (tag.empty()) return;
  const std::lock_guard<std::mutex> lock(mutex);
  if (!done.insert(absoluteText(folder)).second) return;
  struct stat st {};
  if (::lstat((fs::path(folder) / ".vdg-journal").c_str(), &st) == 0) return;
  DIR* dir = ::opendir(folder.c_str());
  if (!dir) return;
  std::vector<std::string> stale;
  while (const dirent* entry = ::readdir(dir)) {
    const long pid = leftoverPid(entry->d_name, tag);
    if (pid <= 0 || pid == ::getpid()) continue;
    if (::kill(static_cast<pid_t>(pid), 0) == 0 || errno != ESRCH) continue;  // running, or not provably gone
    const std::string path = (fs::path(folder) / entry->d_name).string();
    if (::lstat(path.c_str(), &st) == 0 && S_ISREG(st.st_mode) && st.st_uid == ::geteuid()) stale.push_back(path);
  }
  ::closedir(dir);
  for (const std::string& path : stale) ::unlink(path.c_str());
}

// A fresh ".vdg-RRRRRR-PID-TAG" beside `real_target` (".vdg-RRRRRR" when there is no tag).
std::string ownTemporaryPathFor(const std::string& real_target) {
  const std::string& tag = instanceTag();
  std::string name = ".vdg-" + randomSuffix();
  if (!tag.empty()) name += "-" + std::to_string(::getpid()) + "-" + tag;
  const fs::path parent = fs::path(real_target).parent_path();
  return (parent.empty() ? fs::path(name) : parent / name).string();
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

// Whether `path` names one of vdg's own open files (/dev/stdout, /dev/fd/1, /proc/self/fd/1):
// written in place, as the shell opened it, whatever it is.
bool isDescriptorPath(const std::string& path) {
  return path.starts_with("/dev/std") || path.starts_with("/dev/fd/") || path.starts_with("/proc/self/fd/");
}

// Writes to a character device or a FIFO (or a descriptor path, see above) in place.
void writeStream(const std::string& path, const std::string& real, bool fifo, std::string_view contents) {
  const bool descriptor = isDescriptorPath(path);
  const int fd = ::open(real.c_str(), O_WRONLY | O_NOCTTY | O_CLOEXEC | O_NONBLOCK | (descriptor ? O_APPEND : 0));
  if (fd < 0) {
    // /dev/stdout of vdg ... | head -1 once head has gone: the output is no longer wanted.
    if (fifo && errno == ENXIO && descriptor) throw ReaderClosed(path + ": the program reading it has stopped");
    if (fifo && errno == ENXIO) throw Error(path + ": is a FIFO that no program is reading");
    failWrite(path, errno);
  }
  struct stat st {};
  if (::fstat(fd, &st) != 0 ||
      !(S_ISCHR(st.st_mode) || S_ISFIFO(st.st_mode) || S_ISSOCK(st.st_mode) || (descriptor && S_ISREG(st.st_mode)))) {
    ::close(fd);
    throw Error(path + ": changed while being opened; not written");
  }
  // Blocking writes from here on: a FIFO's reader may be slower than vdg.
  const int flags = ::fcntl(fd, F_GETFL);
  if (flags >= 0) (void)::fcntl(fd, F_SETFL, flags & ~O_NONBLOCK);
  int err = writeAll(fd, contents);
  if (::close(fd) != 0 && err == 0 && errno != EINTR) err = errno;
  if (err == EPIPE) throw ReaderClosed(path + ": the program reading it has stopped");
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

std::string checkedOutputPath(const std::string& path) {
  const std::string real = resolveOutputPath(path);
  if (real == path) return real;
  // A link: its real folder must be the link's real folder or beneath it.
  std::error_code ec1, ec2;
  const fs::path link_folder = fs::weakly_canonical(fs::absolute(folderOf(path)), ec1);
  const fs::path real_folder = fs::weakly_canonical(fs::absolute(folderOf(real)), ec2);
  if (ec1 || ec2 || !detail::isPathWithin(real_folder, link_folder))
    throw Error(path + ": is a symbolic link to a file outside its folder (" + real + "); not written through");
  return real;
}

bool isSameFile(const std::string& a, const std::string& b) {
  struct stat sa {
  }, sb{};
  return ::stat(a.c_str(), &sa) == 0 && ::stat(b.c_str(), &sb) == 0 && sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
}

bool makeOutputFolder(const std::string& folder, std::error_code& ec) {
  ec.clear();
  std::vector<fs::path> missing;  // deepest first
  for (fs::path p = fs::path(folder).lexically_normal(); !p.empty() && p != p.root_path(); p = p.parent_path()) {
    if (p.filename().empty()) continue;  // "out/" has an empty last part
    if (fs::exists(fs::symlink_status(p, ec)) || fs::is_directory(p, ec)) break;
    missing.push_back(p);
  }
  ec.clear();
  for (auto it = missing.rbegin(); it != missing.rend(); ++it) {
    // Remembered before it exists, for removeNewOutputs and the interrupt handler, so that an
    // interrupt right after the mkdir still removes it (folders are made by one thread only).
    const int n = g_folder_count.load();
    const std::string made = absoluteText(it->string());
    const bool noted = n < kSlots && made.size() < kSlotPathMax;
    if (noted) {
      std::memcpy(g_folders[n].path, made.c_str(), made.size() + 1);
      g_folders[n].state.store(3);
      g_folder_count.store(n + 1);
    }
    if (::mkdir(it->c_str(), 0777) != 0) {
      const int err = errno;
      if (noted) g_folders[n].state.store(0);  // not made by this run: never removed
      if (err == EEXIST) continue;
      ec = std::error_code(err, std::generic_category());
      return false;
    }
  }
  if (!fs::is_directory(folder, ec) && !ec) ec = std::make_error_code(std::errc::not_a_directory);
  return !ec && !missing.empty();
}

void makeOutputFolder(const std::string& folder) {
  std::error_code ec;
  makeOutputFolder(folder, ec);
  if (ec == std::errc::not_a_directory) throw Error(folder + ": is a file, not a folder");
  if (ec) throw Error(folder + ": cannot make the folder: " + ec.message());
}

void removeNewOutputs() { removeNew(); }

void keepNewOutputs() { g_keep_created.store(true); }

void installOutputSignalHandlers() {
  (void)instanceTag();  // read the boot id now, not in the middle of a write
  ::signal(SIGPIPE, SIG_IGN);
  ::signal(SIGXFSZ, SIG_IGN);
  struct sigaction action {};
  action.sa_handler = onInterrupt;
  sigemptyset(&action.sa_mask);
  for (int sig : {SIGINT, SIGTERM, SIGHUP}) sigaddset(&action.sa_mask, sig);
  for (int sig : {SIGINT, SIGTERM, SIGHUP}) {
    struct sigaction old {};
    // SIGHUP ignored when vdg started (nohup) stays ignored. SIGINT and SIGTERM are always caught:
    // a shell script starts its background jobs with SIGINT ignored, and they must still clean up.
    if (sig == SIGHUP && ::sigaction(sig, nullptr, &old) == 0 && old.sa_handler == SIG_IGN) continue;
    ::sigaction(sig, &action, nullptr);
  }
}

int removeOnInterrupt(const std::string& path) { return claimSlot(g_slots, absoluteText(path), 2); }

void keepOnInterrupt(int token) {
  if (token >= 0 && token < kSlots) g_slots[token].state.store(0);
}

void killOnInterrupt(pid_t group) { g_child_group.store(group); }

std::string temporaryPathFor(const std::string& real_target) {
  return (fs::path(folderOf(real_target)) / (".vdg-" + randomSuffix())).string();
}

namespace {

// Creates the temporary file of `staged_path` (O_EXCL) and registers it for removal on an
// interrupt: `temp_path` when given, else a fresh own name. Returns the open descriptor.
int createTemporary(const std::string& path, const std::string& target, const std::string& temp_path,
                    std::string& temp_out, int& token) {
  const std::string folder = folderOf(target);
  if (temp_path.empty()) removeLeftovers(folder);
  const int attempts = temp_path.empty() ? kMaxAttempts : 1;
  for (int attempt = 0; attempt < attempts; ++attempt) {
    temp_out = temp_path.empty() ? ownTemporaryPathFor(target) : temp_path;
    token = removeOnInterrupt(temp_out);  // before the file exists: an interrupt never misses it
    // 0666 here: the kernel applies the umask, as for any new file.
    const int fd = ::open(temp_out.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd >= 0) return fd;
    const int err = errno;
    keepOnInterrupt(token);  // not ours: never remove it
    token = -1;
    temp_out.clear();
    if (err == EEXIST) continue;
    if (err == ENOENT) throw Error(path + ": cannot write file: the folder " + folder + " does not exist");
    failWrite(path, err);
  }
  failWrite(path, EEXIST);
}

}  // namespace

StagedFile::StagedFile(const std::string& path, std::string_view contents, const std::string& temp_path)
    : path_(path), target_(checkedOutputPath(path)) {
  struct stat st {};
  bool replacing = false;
  if (::stat(target_.c_str(), &st) == 0) {
    if (!S_ISREG(st.st_mode))
      throw Error(path_ + ": is " + detail::fileKindText(st.st_mode) + ", not a file vdg can replace");
    replacing = true;
  }
  const int fd = createTemporary(path_, target_, temp_path, temp_path_, interrupt_token_);
  int err = 0;
  if (replacing) (void)::fchmod(fd, st.st_mode & 07777);  // best effort: set-id bits may be refused
  struct stat written {};
  if (::fstat(fd, &written) == 0) device_ = written.st_dev, inode_ = written.st_ino;
  err = writeAll(fd, contents);
  if (err == 0 && ::fsync(fd) != 0) err = errno;
  if (::close(fd) != 0 && err == 0 && errno != EINTR) err = errno;
  if (err != 0) {
    ::unlink(temp_path_.c_str());
    forget();
    failWrite(path_, err);
  }
}

void StagedFile::forget() {
  temp_path_.clear();
  keepOnInterrupt(interrupt_token_);
  interrupt_token_ = -1;
}

StagedFile::StagedFile(StagedFile&& other) noexcept
    : path_(std::move(other.path_)),
      target_(std::move(other.target_)),
      temp_path_(std::move(other.temp_path_)),
      interrupt_token_(other.interrupt_token_),
      device_(other.device_),
      inode_(other.inode_) {
  other.temp_path_.clear();
  other.interrupt_token_ = -1;
}

StagedFile::~StagedFile() {
  if (!temp_path_.empty()) ::unlink(temp_path_.c_str());
  forget();
}

void StagedFile::commit() {
  assert(!temp_path_.empty() && "StagedFile committed twice");
  struct stat st {};
  // A new file is noted before the rename, so that an interrupt right after it still removes it
  // (until then nothing at the target has the temporary file's inode, and nothing is removed).
  if (::lstat(target_.c_str(), &st) != 0 && errno == ENOENT) noteCreated(target_, device_, inode_);
  if (::rename(temp_path_.c_str(), target_.c_str()) != 0) {
    const int err = errno;
    ::unlink(temp_path_.c_str());
    forget();
    if (err == EISDIR || err == ENOTDIR) throw Error(path_ + ": is a folder, not a file vdg can replace");
    failWrite(path_, err);
  }
  forget();
  syncFolder(folderOf(target_));
}

std::string StagedFile::release() {
  std::string temp = std::move(temp_path_);
  forget();
  return temp;
}

void writeFileAtomically(const std::string& path, std::string_view contents) {
  struct stat st {};
  // A device or a FIFO is written in place, through whatever links name it (/dev/stdout is a link
  // to /proc/self/fd/1, whose own target is no path); only files are replaced, and never through a
  // link that leaves its folder.
  if (::stat(path.c_str(), &st) == 0 &&
      (S_ISCHR(st.st_mode) || S_ISFIFO(st.st_mode) || (isDescriptorPath(path) && S_ISREG(st.st_mode))))
    return writeStream(path, path, S_ISFIFO(st.st_mode), contents);
  const std::string real = checkedOutputPath(path);
  if (::stat(real.c_str(), &st) == 0) {
    if (S_ISCHR(st.st_mode) || S_ISFIFO(st.st_mode)) return writeStream(path, real, S_ISFIFO(st.st_mode), contents);
    if (!S_ISREG(st.st_mode)) throw Error(path + ": is " + detail::fileKindText(st.st_mode) + ", not a file");
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
