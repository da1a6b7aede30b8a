// Reading a user's input file with limits: only regular files are read (a folder, a FIFO, a device
// such as /dev/zero or a socket is refused with a message naming it), and never more than a stated
// number of bytes, so hostile input can neither hang a reader nor exhaust memory. While a
// ScopedReadRoot lives, only files that lie below its folder are read at all.
#pragma once

#include <cstddef>
#include <string>

#include "vdg/geom/error.h"

namespace vdg {

// Size limits of the formats vdg reads (bytes). A file larger than its limit is refused with a
// message naming the file, its size and the limit.
inline constexpr std::size_t kMaxJsonFileBytes = std::size_t{64} << 20;  // manifests, scripts, cameras
inline constexpr std::size_t kMaxMeshFileBytes = std::size_t{2} << 30;   // OBJ meshes

// The whole content of `path`. `what` names the kind of file in messages ("model", "edit script").
// Throws vdg::Error "PATH: ..." when the file is missing, is not a regular file, is unreadable or
// holds more than `max_bytes` bytes.
std::string readFileLimited(const std::string& path, const std::string& what, std::size_t max_bytes);

// Throws the same vdg::Error as readFileLimited would when `path` is not a readable regular file;
// for readers that hand the path to a library.
void checkInputFile(const std::string& path, const std::string& what);

// Thrown instead of a plain Error when a file lies outside the read root: readers that turn an
// unreadable side file (a material library, a texture) into a warning let this one through, so
// every file a load reaches obeys the root as the file given to it does.
class ReadRootError : public Error {
 public:
  using Error::Error;
};

// The read confinement (used by `vdg run` while a script runs): while an object lives, every file
// readFileLimited, checkInputFile and openReadConfined open must be, once opened, a file whose real
// path lies below `root` (the check is made on the open descriptor, through /proc/self/fd, so
// swapping a file for a symbolic link after a check cannot get around it). A file outside is
// refused with ReadRootError "PATH: the WHAT leads outside the read root 'ROOT'", ROOT the root's
// real path. Process-wide (worker threads of a reader obey it too); nested objects replace the
// root and restore the previous one when they end; not for concurrent use from several threads.
// Throws vdg::Error when `root` is not an existing folder.
class ScopedReadRoot {
 public:
  explicit ScopedReadRoot(const std::string& root);
  ~ScopedReadRoot();
  ScopedReadRoot(const ScopedReadRoot&) = delete;
  ScopedReadRoot& operator=(const ScopedReadRoot&) = delete;

 private:
  std::string previous_;
};

// The real path of the current read root; empty when no ScopedReadRoot lives.
std::string currentReadRoot();

// Whether the open descriptor `fd`, opened from `path`, is a file below `folder` (a real path, no
// trailing slash): resolves what was actually opened (/proc/self/fd/FD; without /proc, the real
// path of `path` when it is still the same file). False when it cannot be resolved.
bool openedBelow(int fd, const std::string& path, const std::string& folder);

}  // namespace vdg
